#include "sim/state_file.hpp"

#include <cstring>
#include <fstream>

#include "core/atomic_file.hpp"
#include "core/binary_io.hpp"
#include "core/input_file.hpp"

namespace fluidbed {
namespace {
// 03: the coupler keeps each particle's frozen drag coefficient and its summed drag (02 kept
// per-cell sums; a file of that form cannot continue bit for bit and is refused by name).
constexpr char kGasTag[8] = {'F', 'L', 'B', 'G', 'A', 'S', '0', '3'};
constexpr char kOldGasTag[8] = {'F', 'L', 'B', 'G', 'A', 'S', '0', '2'};
}  // namespace

void save_simulation_state(const std::string& path, const StateFile& f) {
  write_file_atomically(path, [&](std::ostream& out) {
    write_state(out, f.dem);
    if (!f.has_gas) return;
    out.write(kGasTag, sizeof kGasTag);
    const GasState& g = f.gas;
    for (const auto* v : {&g.u, &g.v, &g.p, &g.eps, &g.preconditioner_u, &g.preconditioner_v,
                          &g.u_previous, &g.v_previous})
      put_vec(out, *v);
    put(out, g.dt_previous);
    put(out, g.superficial_velocity);
    put(out, g.time);
    put(out, g.steps);
    const CouplingState& c = f.coupling;
    put_vec(out, c.eps);
    put_vec(out, c.cell);
    for (const auto* v : {&c.beta, &c.gas_ux, &c.gas_uy, &c.base_fx, &c.base_fy, &c.drag_x,
                          &c.drag_y, &c.sum_x, &c.sum_y})
      put_vec(out, *v);
    put(out, c.accumulated);
    put(out, f.since_gas_step);
  });
}

StateFile load_simulation_state(const std::string& path) {
  std::ifstream in = open_input_file(path, "state file");
  StateFile f;
  f.dem = read_state(in, path);
  char tag[sizeof kGasTag];
  in.read(tag, sizeof tag);
  if (in.gcount() == 0) return f;  // particles only
  if (in && std::memcmp(tag, kOldGasTag, sizeof tag) == 0)
    throw InputError(path + ": the gas block was saved by an older fluidbed (format 02) and "
                            "cannot be continued; its particles still start a new run "
                            "(particles.placement = \"state\")");
  if (!in || std::memcmp(tag, kGasTag, sizeof tag) != 0)
    throw InputError(path + ": state file has an unknown block after the particles");
  f.has_gas = true;
  BinarySource src(in, path);
  GasState& g = f.gas;
  for (auto* v : {&g.u, &g.v, &g.p, &g.eps, &g.preconditioner_u, &g.preconditioner_v,
                  &g.u_previous, &g.v_previous})
    src.get_vec(*v);
  g.dt_previous = src.get<double>();
  g.superficial_velocity = src.get<double>();
  g.time = src.get<double>();
  g.steps = src.get<std::int64_t>();
  CouplingState& c = f.coupling;
  src.get_vec(c.eps);
  src.get_vec(c.cell);
  for (auto* v : {&c.beta, &c.gas_ux, &c.gas_uy, &c.base_fx, &c.base_fy, &c.drag_x, &c.drag_y,
                  &c.sum_x, &c.sum_y})
    src.get_vec(*v);
  c.accumulated = src.get<int>();
  f.since_gas_step = src.get<int>();
  return f;
}

}  // namespace fluidbed
