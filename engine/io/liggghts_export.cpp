#include "io/liggghts_export.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"
#include "core/text_format.hpp"
#include "dem/contact_law.hpp"
#include "dem/walls.hpp"
#include "scene/scene_loader.hpp"
#include "sim/model_params.hpp"
#include "sim/placement.hpp"

namespace fluidbed {
namespace {

constexpr const char* kDeckName = "in.liggghts";
constexpr const char* kDataName = "particles.data";
constexpr const char* kDumpName = "final.dump";

// Numbers as the shortest text that reads back as the same double: the files hold exactly the
// scene's numbers.
std::string num(double v) { return shortest_number(v); }

ContactParams contact_params(const Settings& s) { return dem_params_for(s).contact; }

bool same_law(const ContactParams& a, const ContactParams& b) {
  return a.kn == b.kn && a.kt == b.kt && a.eta_n == b.eta_n && a.eta_t == b.eta_t && a.mu == b.mu &&
         a.mu_r == b.mu_r;
}

void check_integrator(const Settings& s, const std::string& what) {
  if (s.contact.law == ContactLaw::HertzMindlin)
    throw InputError(what +
                     "contact.law \"hertz_mindlin\": the LIGGGHTS export writes the linear law "
                     "(model hooke) only; export the scene with contact.law = \"linear\"");
  if (s.time.integrator == Integrator::SymplecticEuler)
    throw InputError(what +
                     "time.integrator \"symplectic_euler\": LIGGGHTS integrates with velocity "
                     "Verlet (fix nve/sphere), second order; export with --set "
                     "time.integrator=velocity_verlet (or newmark) to compare like with like");
}

// The packing stage of a "packed" start: the scene whose law packs the bed (this one, or
// particles.packing_scene), checked like packed_bed_state checks it.
struct PackingStage {
  ContactParams law;
  double dt = 0.0, seconds = 0.0, gravity = 0.0;
  std::string from;  // scene file the law comes from ("" for this scene)
};

// The packing's own friction where the packing scene gives it (settings.hpp), as
// packing_settings_for packs with it.
PackingStage with_packing_friction(PackingStage st, const Settings& packing) {
  if (packing.particles.packing_friction) st.law.mu = *packing.particles.packing_friction;
  if (packing.particles.packing_rolling_friction)
    st.law.mu_r = *packing.particles.packing_rolling_friction;
  return st;
}

PackingStage packing_stage(const Settings& s) {
  PackingStage st;
  st.law = contact_params(s);
  st.dt = s.time.dt;
  st.gravity = s.physics.gravity;
  st.seconds = s.particles.packing_time;
  if (s.particles.packing_scene.empty()) return with_packing_friction(st, s);
  const std::string path = scene_path(s, s.particles.packing_scene);
  const Settings other = load_scene(path);
  if (other.particles.count != s.particles.count ||
      other.particles.diameter != s.particles.diameter)
    throw InputError("particles.packing_scene " + s.particles.packing_scene +
                     " packs different particles (count or diameter) than this scene");
  if (other.particles.density != s.particles.density || other.domain.width != s.domain.width ||
      other.domain.height != s.domain.height || other.domain.top_wall != s.domain.top_wall)
    throw InputError("particles.packing_scene " + s.particles.packing_scene +
                     ": its density or domain differs from this scene's; the deck can change the "
                     "contact law between stages, not the particles or the walls");
  check_integrator(other, "particles.packing_scene " + s.particles.packing_scene + ": ");
  st.law = contact_params(other);
  st.dt = other.time.dt;
  st.gravity = other.physics.gravity;
  st.from = s.particles.packing_scene;
  return with_packing_friction(st, other);
}

// The particles at the start of the deck.
Particles start_particles(const Settings& s) {
  switch (s.particles.placement) {
    case Placement::Lattice:
    case Placement::Single: return place_particles(s);
    case Placement::Packed: {
      Settings lattice = s;
      lattice.particles.placement = Placement::Lattice;
      return place_particles(lattice);
    }
    case Placement::State: return load_scene_state(s).particles;
  }
  throw InputError("particles.placement \"" + option_string(s.particles.placement) +
                   "\": the LIGGGHTS export knows lattice, single, state and packed");
}

double box_top(const Settings& s) {
  // Open top: fluidbed fails a run when a centre passes height + radius; LIGGGHTS loses a sphere
  // that leaves its box and, with `thermo_modify lost error`, stops there too.
  return s.domain.top_wall ? s.domain.height : s.domain.height + 0.5 * s.particles.diameter;
}

void write_data(std::ostream& out, const Settings& s, const Particles& p) {
  const double z = 0.5 * s.domain.thickness;
  out << "LIGGGHTS data file: fluidbed scene \"" << s.scene.name << "\", " << p.size()
      << " spheres (Atoms: id type diameter density x y z)\n\n";
  out << p.size() << " atoms\n1 atom types\n\n";
  out << "0 " << num(s.domain.width) << " xlo xhi\n";
  out << "0 " << num(box_top(s)) << " ylo yhi\n";
  out << "0 " << num(s.domain.thickness) << " zlo zhi\n\nAtoms\n\n";
  const std::string d = num(s.particles.diameter), rho = num(s.particles.density), zs = num(z);
  const bool depth = p.has_depth();  // a thick slab: each sphere's own z, velocity and spin
  for (std::size_t i = 0; i < p.size(); ++i)
    out << i + 1 << " 1 " << d << ' ' << rho << ' ' << num(p.x[i]) << ' ' << num(p.y[i]) << ' '
        << (depth ? num(p.z[i]) : zs) << '\n';
  bool moving = false;
  for (std::size_t i = 0; i < p.size(); ++i)
    moving = moving || p.vx[i] != 0.0 || p.vy[i] != 0.0 || p.w[i] != 0.0 ||
             (depth && (p.vz[i] != 0.0 || p.wx[i] != 0.0 || p.wy[i] != 0.0));
  if (!moving) return;
  out << "\nVelocities\n\n";  // id vx vy vz omegax omegay omegaz
  for (std::size_t i = 0; i < p.size(); ++i) {
    out << i + 1 << ' ' << num(p.vx[i]) << ' ' << num(p.vy[i]) << ' ';
    if (depth)
      out << num(p.vz[i]) << ' ' << num(p.wx[i]) << ' ' << num(p.wy[i]);
    else
      out << "0 0 0";
    out << ' ' << num(p.w[i]) << '\n';
  }
}

// fix property/global blocks: LIGGGHTS reads the law's numbers from these, for every pair of
// atom types (one type here: particles and walls alike). Issued again with the same ids, they
// replace the previous values for the next run.
void write_law(std::ostream& out, const ContactParams& c, bool rolling) {
  out << "fix kn     all property/global kn peratomtypepair 1 " << num(c.kn) << "     # N/m\n";
  out << "fix kt     all property/global kt peratomtypepair 1 " << num(c.kt) << "     # N/m\n";
  out << "fix gamman all property/global gamman_abs peratomtypepair 1 " << num(c.eta_n)
      << "   # kg/s\n";
  out << "fix gammat all property/global gammat_abs peratomtypepair 1 " << num(c.eta_t)
      << "   # kg/s\n";
  out << "fix mu     all property/global coefficientFriction peratomtypepair 1 " << num(c.mu)
      << '\n';
  if (rolling)
    out << "fix rmu    all property/global coefficientRollingFriction peratomtypepair 1 "
        << num(c.mu_r) << '\n';
}

// One item of a list in the deck's comments, wrapped to lines of at most 96 characters.
void write_comment(std::ostream& out, const std::string& text) {
  std::istringstream words(text);
  std::string line = "#  -";
  for (std::string w; words >> w;) {
    if (line.size() + 1 + w.size() > 96) {
      out << line << '\n';
      line = "#   ";
    }
    line += ' ' + w;
  }
  out << line << '\n';
}

struct Plane {
  const char* id;
  const char* axis;  // xplane, yplane, zplane
  double at;         // m
};

void write_deck(std::ostream& out, const Settings& s, const LiggghtsExportOptions& o,
                const std::vector<std::string>& notes) {
  const ContactParams law = contact_params(s);
  const bool packed = s.particles.placement == Placement::Packed;
  const PackingStage pack = packed ? packing_stage(s) : PackingStage{};
  // contact.rolling_friction: LIGGGHTS' constant directional torque (cdt), mu_r R_eff |F_n|
  // against the relative rotation, as fluidbed's (which takes F_n as the spring's force).
  const bool rolling = law.mu_r > 0.0 || (packed && pack.law.mu_r > 0.0);
  const std::string model = std::string("model hooke/stiffness tangential history") +
                            (rolling ? " rolling_friction cdt" : "");
  const double dt0 = packed ? pack.dt : s.time.dt;
  const double g0 = packed ? pack.gravity : s.physics.gravity;

  out << "# LIGGGHTS 3.8 input deck for the fluidbed scene \"" << s.scene.name << "\"\n";
  if (!s.scene.description.empty()) out << "# (" << s.scene.description << ")\n";
  out << "# written by `fluidbed export SCENE --to liggghts DIR`; the particles' start is in "
      << kDataName << ".\n#\n";
  out << "# Run it in this folder:\n";
  out << "#   liggghts -in " << kDeckName << "                 one process\n";
  out << "#   mpirun -np 4 liggghts -in " << kDeckName
      << "    MPI: the bed is cut in x and y, never in z\n";
  out << "# It writes log.liggghts (thermo: kinetic energy every "
      << num(s.diagnostics.output_interval) << " s of simulated time)\n# and " << kDumpName
      << " (every sphere at the end).\n#\n";
  out << "# SI units. x across the bed (0 to " << num(s.domain.width) << " m), y up (0 to "
      << num(s.domain.height) << " m), z through the slab (0 to " << num(s.domain.thickness)
      << " m).\n# The spheres move in x-y on the slab's mid-plane and spin about z.\n#\n";
  out << "# The same particles, contact law, walls, gravity, time step and run length as "
         "fluidbed;\n"
      << "# the differences:\n";
  for (const std::string& n : notes) write_comment(out, n);
  out << '\n';

  out << "units           si\n";
  out << "atom_style      sphere\n";
  out << "atom_modify     map array\n";
  out << "boundary        f f f          # the box is the bed; a sphere leaving it is an error\n";
  out << "newton          off\n";
  out << "communicate     single vel yes # granular contacts need the neighbours' velocities\n";
  out << "processors      * * 1          # one layer of sub-domains through the thin slab\n\n";

  out << "read_data       " << kDataName << '\n';
  out << "neighbor        " << num(s.contact.skin * s.particles.diameter)
      << " bin   # m, neighbour-list skin (contact.skin diameters)\n";
  out << "neigh_modify    delay 0\n\n";

  out << "# Contact law (fluidbed's contact_law.hpp; Xu & Yu 1997 eqs 3-7): linear springs\n"
      << "# kn, kt, absolute viscous damping gamman_abs, gammat_abs (not scaled by the mass),\n"
      << "# Coulomb friction with the tangential spring held at the limit while sliding.\n";
  if (packed && !same_law(pack.law, law))
    out << "# The packing stage below uses the law of " << pack.from
        << "; the scene's own law replaces it after the packing.\n";
  write_law(out, packed ? pack.law : law, rolling);
  out << "pair_style      gran " << model << " absolute_damping on\n";
  out << "pair_coeff      * *\n\n";

  out << "timestep        " << num(dt0) << "   # s\n";
  out << "fix gravity all gravity " << num(g0) << " vector 0.0 -1.0 0.0   # m/s^2, along -y\n\n";

  out << "# Walls: planes with the particles' law (atom type 1).\n";
  if (!o.front_back_walls)
    out << "# No front and back walls: they never press on a sphere that moves in-plane; the z\n"
        << "# force is held at zero instead (fix planar), so z velocity stays at its start, 0.\n";
  std::vector<Plane> planes = {{"wall_left", "xplane", 0.0},
                               {"wall_right", "xplane", s.domain.width},
                               {"wall_bottom", "yplane", 0.0}};
  if (s.domain.top_wall) planes.push_back({"wall_top", "yplane", s.domain.height});
  if (o.front_back_walls) {
    planes.push_back({"wall_front", "zplane", 0.0});
    planes.push_back({"wall_back", "zplane", s.domain.thickness});
  }
  for (const Plane& pl : planes)
    out << "fix " << pl.id << " all wall/gran " << model << " &\n    primitive type 1 " << pl.axis
        << ' ' << num(pl.at) << " absolute_damping on\n";
  out << '\n';

  out << "fix integrate all nve/sphere     # velocity Verlet, translation and rotation\n";
  if (!o.front_back_walls)
    out << "fix planar all setforce NULL NULL 0.0   # z force 0: motion in x-y only\n";
  out << '\n';

  const std::int64_t every =
      std::max<std::int64_t>(1, steps_for(s.diagnostics.output_interval, s.time.dt));
  out << "# Output: kinetic energy of translation (ke) and rotation (c_erot), J, whole bed.\n";
  out << "compute erot all erotate/sphere\n";
  out << "variable ke_total equal ke+c_erot\n";
  out << "thermo_style    custom step atoms ke c_erot v_ke_total\n";
  out << "thermo_modify   norm no lost error\n";
  if (packed) {
    const std::int64_t pack_steps = steps_for(pack.seconds, pack.dt);
    const std::int64_t pack_every =
        std::max<std::int64_t>(1, steps_for(s.diagnostics.output_interval, pack.dt));
    out << "thermo          " << pack_every << "   # steps: diagnostics.output_interval\n\n";
    out << "# Stage 1, the packing (particles.placement = \"packed\"): the lattice start falls for "
        << num(pack.seconds) << " s\n# (particles.packing_time), the gas left out.\n";
    out << "run             " << pack_steps << "   # " << num(pack.seconds) << " s\n\n";
    out << "# Stage 2, the scene's run from the packed bed, its clock restarted.\n";
    out << "reset_timestep  0\n";
    if (!same_law(pack.law, law)) write_law(out, law, rolling);
    if (pack.dt != s.time.dt) out << "timestep        " << num(s.time.dt) << "   # s\n";
    if (pack.gravity != s.physics.gravity)
      out << "fix gravity all gravity " << num(s.physics.gravity) << " vector 0.0 -1.0 0.0\n";
    if (pack_every != every) out << "thermo          " << every << "   # steps\n";
    out << '\n';
  } else {
    out << "thermo          " << every << "   # steps: diagnostics.output_interval\n\n";
  }
  const std::int64_t steps = steps_for(s.time.end, s.time.dt);
  if (o.frames_every > 0.0) {
    const std::int64_t frame_steps = std::max<std::int64_t>(1, steps_for(o.frames_every, s.time.dt));
    out << "# Every sphere every " << num(o.frames_every) << " s, full precision (export option frames_every).\n";
    out << "dump frames all custom " << frame_steps << " frames.dump id type radius x y z vx vy vz omegaz\n";
    out << "dump_modify frames sort id format \"%d %d";
    for (int k = 0; k < 8; ++k) out << " %.15g";
    out << "\"\n\n";
  }
  out << "run             " << steps << "   # time.end = " << num(s.time.end)
      << " s at dt = " << num(s.time.dt) << " s\n\n";
  out << "# Every sphere at the end, sorted by id: fluidbed measures the bed height from it (mean\n"
      << "# over 1 cm columns of the highest centre) and the solid fraction.\n";
  out << "write_dump all custom " << kDumpName << " id type radius x y z vx vy vz omegaz &\n"
      << "    modify sort id format \"%d %d";
  for (int k = 0; k < 8; ++k) out << " %.15g";
  out << "\"\n";
}

std::vector<std::string> notes_for(const Settings& s, const LiggghtsExportOptions& o) {
  std::vector<std::string> n;
  if (s.gas.enabled) {
    std::string g = "the gas is left out: LIGGGHTS is DEM only, so the scene's [gas] (" +
                    std::to_string(s.gas.cells_x) + " x " + std::to_string(s.gas.cells_y) +
                    " cells, inlet \"" + option_string(s.inlet.kind) + "\"";
    if (s.inlet.kind != InletKind::None) g += ", U = " + num(s.inlet.superficial_velocity) + " m/s";
    g += ") exerts no drag or pressure force here";
    n.push_back(g);
  }
  n.push_back("LIGGGHTS integrates with velocity Verlet (fix nve/sphere); the scene uses \"" +
              option_string(s.time.integrator) + "\"");
  if (s.contact.displacement == Displacement::Incremental)
    n.push_back(
        "the normal overlap is geometric, R_i + R_j - |x_i - x_j|; the scene accumulates it "
        "from increments (\"incremental\", eqs 13-17); the tangential displacement is "
        "accumulated in both");
  n.push_back(
      "sliding caps the tangential force at mu times the whole normal force (spring and "
      "dashpot); fluidbed caps it at mu times the spring force");
  if (slab_has_depth(s.domain, s.particles.diameter))
    n.push_back("a thick slab: the spheres move in 3D and the front and back walls are "
                "wall/gran planes, as in fluidbed");
  else
    n.push_back(o.front_back_walls
                    ? "the front and back walls are wall/gran planes (fluidbed leaves them out: "
                      "they never press on an in-plane sphere)"
                    : "no front and back walls, as in fluidbed; the z force is held at zero "
                      "instead, so the spheres stay on the mid-plane");
  if (s.particles.placement == Placement::State)
    n.push_back("the start is the saved state " + s.particles.state_file +
                " without its contact history: tangential springs start at zero");
  if (s.particles.placement == Placement::Packed)
    n.push_back(
        "the packed start is made by this deck, as a first stage (the lattice start falls "
        "for particles.packing_time), without the gas");
  return n;
}

}  // namespace

LiggghtsCase write_liggghts_case(const Settings& s, const std::string& dir,
                                 const LiggghtsExportOptions& options) {
  if (s.particles.frozen)
    throw InputError(
        "particles.frozen: a fixed bed only lets the gas through, and LIGGGHTS has "
        "no gas; there is nothing to export");
  check_integrator(s, "");
  if (s.contact.wall_friction)
    throw InputError("contact.wall_friction: the deck's walls take the particles' law (one atom "
                     "type), so walls with their own friction are not exported (leave it unset)");
  const Particles p = start_particles(s);
  // A thick slab's spheres move in z: the front and back walls are contacts there as here.
  LiggghtsExportOptions o = options;
  o.front_back_walls = o.front_back_walls || p.has_depth();
  const std::vector<std::string> notes = notes_for(s, o);
  // Render the deck before touching the folder, so that a refusal writes nothing.
  std::ostringstream deck;
  write_deck(deck, s, o, notes);

  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("cannot create " + dir + ": " + ec.message());
  LiggghtsCase c;
  c.deck = (fs::path(dir) / kDeckName).string();
  c.data = (fs::path(dir) / kDataName).string();
  c.notes = notes;
  write_file_atomically(c.data, [&](std::ostream& out) { write_data(out, s, p); });
  write_file_atomically(c.deck, [&](std::ostream& out) { out << deck.str(); });
  return c;
}

std::vector<LiggghtsFrame> read_liggghts_frames(const std::string& path, double density) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path);
  auto bad = [&](const std::string& why) { return InputError(path + ": " + why); };
  std::vector<LiggghtsFrame> frames;
  std::int64_t step = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("ITEM: TIMESTEP", 0) == 0) {
      if (!std::getline(in, line) || !(std::istringstream(line) >> step)) throw bad("no step after ITEM: TIMESTEP");
      continue;
    }
    if (line.rfind("ITEM: NUMBER OF ATOMS", 0) != 0) continue;
    long long n = -1;
    if (!std::getline(in, line) || !(std::istringstream(line) >> n) || n < 0)
      throw bad("no atom count after ITEM: NUMBER OF ATOMS");
    while (std::getline(in, line) && line.rfind("ITEM: ATOMS", 0) != 0) {
    }
    if (line.rfind("ITEM: ATOMS", 0) != 0) throw bad("a snapshot without ITEM: ATOMS");
    std::istringstream head(line.substr(11));
    std::vector<std::string> cols;
    for (std::string c; head >> c;) cols.push_back(c);
    auto find = [&](const char* name) {
      return static_cast<std::size_t>(std::find(cols.begin(), cols.end(), name) - cols.begin());
    };
    auto col = [&](const char* name) {
      const std::size_t c = find(name);
      if (c == cols.size()) throw bad(std::string("no \"") + name + "\" column");
      return c;
    };
    const std::size_t cid = col("id"), cr = col("radius"), cx = col("x"), cy = col("y");
    const std::size_t cvx = find("vx"), cvy = find("vy"), cw = find("omegaz");
    std::map<long long, std::array<double, 6>> rows;  // id -> radius, x, y, vx, vy, omegaz
    std::vector<double> v(cols.size());
    for (long long k = 0; k < n; ++k) {
      if (!std::getline(in, line)) throw bad("the file ends inside a snapshot");
      std::istringstream row(line);
      for (double& value : v)
        if (!(row >> value)) throw bad("a short row: " + line);
      auto opt = [&](std::size_t c) { return c < v.size() ? v[c] : 0.0; };
      rows[std::llround(v[cid])] = {v[cr], v[cx], v[cy], opt(cvx), opt(cvy), opt(cw)};
    }
    LiggghtsFrame f;
    f.step = step;
    f.particles.resize(rows.size());
    std::size_t i = 0;
    for (const auto& [id, a] : rows) {
      f.particles.set_sphere(i, 2.0 * a[0], density);
      f.particles.x[i] = a[1];
      f.particles.y[i] = a[2];
      f.particles.vx[i] = a[3];
      f.particles.vy[i] = a[4];
      f.particles.w[i] = a[5];
      ++i;
    }
    frames.push_back(std::move(f));
  }
  if (frames.empty()) throw bad("no snapshot");
  return frames;
}

Particles read_liggghts_dump(const std::string& path, double density) {
  return std::move(read_liggghts_frames(path, density).back().particles);
}

}  // namespace fluidbed
