// Binary state files for bit-exact restarts: positions, velocities, spins, accelerations, radii
// and masses, pair and wall contact history, time and step.
#include <cstring>
#include <fstream>

#include "core/atomic_file.hpp"
#include "core/binary_io.hpp"
#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "dem/dem_solver.hpp"

namespace fluidbed {
namespace {

constexpr char kMagic[8] = {'F', 'L', 'B', 'S', 'T', 'A', 'T', 'E'};
// Version 2: a monolayer; 3: a thick slab, whose depth arrays and shear vectors follow version
// 2's contents (so a monolayer's file is the same bytes as before thick slabs existed). 4 and 5:
// 2 and 3 followed by the solver's order of the particles (DemState::order), for a state saved
// after the solver renumbered them; the rest is in ids, as in 2 and 3.
constexpr std::uint32_t kVersion = 2;
constexpr std::uint32_t kVersionDepth = 3;
constexpr std::uint32_t kOrdered = 2;  // added to either for a state with an order

}  // namespace

void write_state(std::ostream& out, const DemState& s) {
  out.write(kMagic, sizeof kMagic);
  const auto& P = s.particles;
  put(out, (P.has_depth() ? kVersionDepth : kVersion) + (s.order.empty() ? 0 : kOrdered));
  put(out, static_cast<std::uint64_t>(P.size()));
  put(out, static_cast<std::int32_t>(s.walls.walls));
  put(out, s.time);
  put(out, s.step);
  for (const auto* v : {&P.x, &P.y, &P.vx, &P.vy, &P.w, &P.ax, &P.ay, &P.aw, &P.fx, &P.fy,
                        &P.torque, &P.ext_fx, &P.ext_fy, &P.radius, &P.mass, &P.inv_mass,
                        &P.inv_inertia})
    put_vec(out, *v);
  put_vec(out, s.pairs.i);
  put_vec(out, s.pairs.j);
  put_vec(out, s.pairs.dn);
  put_vec(out, s.pairs.ds);
  put_vec(out, s.walls.active);
  put_vec(out, s.walls.dn);
  put_vec(out, s.walls.ds);
  if (P.has_depth()) {
    for (const auto* v : P.depth_arrays()) put_vec(out, *v);
    put_vec(out, s.pairs.ds_y);
    put_vec(out, s.pairs.ds_z);
    put_vec(out, s.walls.ds_y);
    put_vec(out, s.walls.ds_z);
  }
  if (!s.order.empty()) put_vec(out, s.order);
}

DemState read_state(std::istream& in, const std::string& origin) {
  BinarySource src(in, origin);
  char magic[sizeof kMagic];
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw InputError(origin + ": not a fluidbed state file");
  const auto stored = src.get<std::uint32_t>();
  if (stored < kVersion || stored > kVersionDepth + kOrdered)
    throw InputError(origin + ": state file version is not supported");
  const bool ordered = stored > kVersionDepth;
  const std::uint32_t version = ordered ? stored - kOrdered : stored;
  DemState s;
  const auto count = src.get<std::uint64_t>();
  if (count == 0 || count > (1ULL << 31)) src.fail("inconsistent (count)");
  const auto n = static_cast<std::int64_t>(count);
  const auto walls = src.get<std::int32_t>();
  if (walls < 0 || walls > 16) throw InputError(origin + ": state file is inconsistent (walls)");
  s.time = src.get<double>();
  s.step = src.get<std::int64_t>();
  auto& P = s.particles;
  for (auto* v : {&P.x, &P.y, &P.vx, &P.vy, &P.w, &P.ax, &P.ay, &P.aw, &P.fx, &P.fy, &P.torque,
                  &P.ext_fx, &P.ext_fy, &P.radius, &P.mass, &P.inv_mass, &P.inv_inertia})
    src.get_vec(*v, n);
  src.get_vec(s.pairs.i);
  src.get_vec(s.pairs.j, static_cast<std::int64_t>(s.pairs.i.size()));
  src.get_vec(s.pairs.dn, static_cast<std::int64_t>(s.pairs.i.size()));
  src.get_vec(s.pairs.ds, static_cast<std::int64_t>(s.pairs.i.size()));
  s.walls.walls = walls;
  src.get_vec(s.walls.active, n * walls);
  src.get_vec(s.walls.dn, n * walls);
  src.get_vec(s.walls.ds, n * walls);
  if (version == kVersionDepth) {
    for (auto* v : P.depth_arrays()) src.get_vec(*v, n);
    const auto pairs = static_cast<std::int64_t>(s.pairs.i.size());
    src.get_vec(s.pairs.ds_y, pairs);
    src.get_vec(s.pairs.ds_z, pairs);
    src.get_vec(s.walls.ds_y, n * walls);
    src.get_vec(s.walls.ds_z, n * walls);
  }
  if (ordered) src.get_vec(s.order, n);  // a permutation: checked by DemSolver::set_state
  // Pairs: i < j, inside the particle range, sorted by (i, j).
  for (std::size_t k = 0; k < s.pairs.size(); ++k) {
    const auto i = s.pairs.i[k], j = s.pairs.j[k];
    const bool sorted =
        k == 0 || s.pairs.i[k - 1] < i || (s.pairs.i[k - 1] == i && s.pairs.j[k - 1] < j);
    if (i < 0 || i >= j || j >= n || !sorted)
      throw InputError(origin + ": state file is inconsistent (contact pairs)");
  }
  return s;
}

void save_state_file(const std::string& path, const DemState& s) {
  write_file_atomically(path, [&](std::ostream& out) { write_state(out, s); });
}

DemState load_state_file(const std::string& path) {
  std::ifstream in = open_input_file(path, "state file");
  return read_state(in, path);
}

}  // namespace fluidbed
