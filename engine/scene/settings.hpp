#pragma once
// Scene settings: one plain struct per TOML section, defaults from the paper (Xu & Yu 1997,
// Table 1), the unit of every field beside it. `visit_fields` lists each section's keys once with
// their unit, range and help, so the loader, the validator, the resolved-scene writer, `fluidbed
// keys` and the tests all see the same names.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/field_info.hpp"
#include "scene/options.hpp"

namespace fluidbed {

struct SceneInfo {
  std::string name = "unnamed";
  // What the run measures on top of the common diagnostics: "bed" (none extra), "drop" (bounce
  // heights and restitution), "packing" (bed height and solid fraction).
  SceneKind kind = SceneKind::Bed;
  std::string description;
};

struct DomainSettings {
  double width = 0.15;      // m, x extent (left wall at x = 0)
  double height = 0.9;      // m, y extent (bottom wall at y = 0)
  double thickness = 0.004; // m, z extent of the slab between front and back walls
  bool top_wall = false;    // a rigid wall at y = height (the paper's bed is open at the top)
};

struct ParticleSettings {
  int count = 2400;          // number of spheres
  double diameter = 0.004;   // m
  double density = 2700.0;   // kg/m^3
  // "lattice": the paper's packing start (cells of one diameter, alternate rows shifted by a
  // radius, particles in randomly chosen cells); "single": one particle at (x, y);
  // "state": positions, velocities, spins and contact history from state_file;
  // "packed": the paper's packing of this scene's particles (lattice start, gas at rest, falling
  // for packing_time), generated once and cached.
  Placement placement = Placement::Lattice;
  std::uint64_t seed = 1;    // random placement
  double fill_height = 0.0;  // m, lattice cells only below this height (0: the whole domain)
  double x = 0.075;          // m, "single" placement
  double y = 0.05;           // m
  double vx = 0.0;           // m/s
  double vy = 0.0;           // m/s
  double spin = 0.0;         // rad/s about z
  std::string state_file;    // "state" placement; relative paths are relative to the scene file
  double packing_time = 0.8; // s, "packed" placement: how long the lattice start falls
  // "packed" placement: a scene whose settings make the packing instead of this one's (e.g. a
  // frictionless, undamped bed that never settles packs as the realistic one). Relative paths
  // are relative to this scene file. Empty: this scene.
  std::string packing_scene;
  // "packed" placement: the packing's own Coulomb and rolling friction (unset: contact.friction
  // and contact.rolling_friction). Peers load a bed with other contact values than they fluidize
  // it with (Lethe's pseudo-2D bed packs with a rolling friction of 0.2, then runs with 0.025).
  std::optional<double> packing_friction, packing_rolling_friction;
  bool frozen = false;       // held in place (a fixed bed): the gas flows through, nothing moves
};

struct ContactSettings {
  double stiffness = 50000.0;             // N/m, kappa_n
  double tangential_stiffness_ratio = 1.0;  // kappa_t / kappa_n (the paper: 1)
  double damping = 0.15;                  // kg/s, eta_n
  double tangential_damping_ratio = 1.0;  // eta_t / eta_n (the paper: 1)
  double friction = 0.3;                  // gamma, particles (and walls, unless wall_friction)
  // gamma at the walls (unset: friction). A bed a few spheres deep touches its front and back
  // walls everywhere; peers give the walls their own value.
  std::optional<double> wall_friction;
  // Rolling resistance mu_r (the paper's model has none: 0): a torque mu_r R_r |F_n| against the
  // contact's relative rolling, R_r = R_i R_j / (R_i + R_j) for a pair and R_i at a wall.
  double rolling_friction = 0.0;
  // "incremental": the paper's eqs 13-17 (displacements accumulated from increments, the first
  // one over the backward-projected time since touching); "geometric": delta_n = R_i + R_j - L.
  Displacement displacement = Displacement::Incremental;
  // "linear": eqs 3-7 with stiffness and damping above. "hertz_mindlin": each contact's springs
  // and dashpots from its overlap (dem/contact_law.hpp: hertz_params), the walls of the particles'
  // material; the three below are then needed (and refused with "linear").
  ContactLaw law = ContactLaw::Linear;
  std::optional<double> youngs_modulus;  // Pa
  std::optional<double> poisson_ratio;
  std::optional<double> restitution;  // of a head-on impact, pairs and walls
  // Neighbour-list skin as a fraction of the largest diameter: candidate pairs are kept while
  // closer than R_i + R_j + skin, and the list is rebuilt when a particle has moved half of it.
  // Only the speed depends on it, never the results. 0.4 measured fastest (0.2 to 0.5 tried on
  // the packing, the paper's bed and the teaching bed: half the rebuilds of 0.2, and the extra
  // candidates cost less than the rebuilds they save).
  double skin = 0.4;
  // Steps between renumberings of the particles by neighbour cell (DemSolver::renumber): 0 never,
  // -1 automatic: every kAutoRenumberSteps steps in a bed whose particles' arrays leave the cache
  // (sim/model_params.hpp). Only the speed and the results' last bits depend on it.
  int renumber_steps = -1;
};

struct TimeSettings {
  double dt = 1.5e-5;  // s
  double end = 1.0;    // s, simulated time of a run (--until overrides)
  // "newmark" (the paper's predictor-corrector, eqs 24-28), "velocity_verlet", "symplectic_euler"
  Integrator integrator = Integrator::Newmark;
};

struct PhysicsSettings {
  double gravity = 9.81;  // m/s^2, along -y
};

// The gas (section 3). A scene without a [gas] section has none; with one, `enabled` defaults
// to true.
struct GasSettings {
  bool enabled = false;
  double density = 1.205;     // kg/m^3, air
  double viscosity = 1.8e-5;  // Pa s
  int cells_x = 15;           // the paper: dx = 10 mm
  int cells_y = 45;           // the paper: dy = 20 mm
  double tolerance = 1e-6;    // SIMPLE: mass residual relative to the inflow
  int max_iterations = 50;    // SIMPLE iterations per gas step
  // The pressure correction's preconditioner (an exact factorization of an earlier matrix) is
  // made anew when a face coefficient has moved by more than this fraction since (speed only:
  // the correction is solved to its tolerance either way).
  double preconditioner_refresh = 2e-3;
};

struct InletSettings {
  // "jet": a plug through a slot at the centre of the bottom (the paper); "uniform": a
  // distributor over the whole bottom; "none": a closed bottom (gas at rest).
  InletKind kind = InletKind::Jet;
  double superficial_velocity = 2.8;  // m/s, mean over the bottom (jet: U width / jet_width)
  double jet_width = 0.01;            // m, width of each jet's slot
  // Jets along the bottom, slot k centred at (k + 1/2) width / jets (1: the paper's central
  // jet; a bed n times wider with n jets is n paper beds side by side).
  int jets = 1;
  // m: the gas enters this far below the particles' floor, which it crosses freely (Lethe's van
  // Wachem example: 4 cm under a floor wall permeable to the gas). 0: at the floor.
  double plenum_height = 0.0;
  // Pa s/m: a distributor plate at the floor, over a plenum, that resists the gas in proportion
  // to the flow through it (a porous plate, Darcy's law): its pressure drop per m/s of
  // superficial velocity. 0: the floor lets the gas cross freely, as Lethe's floating wall.
  double distributor_resistance = 0.0;
};

struct CouplingSettings {
  // Model A (Feng & Yu 2004; model.md 2.1): particles feel drag and -V grad p. false: the paper's
  // printed form, drag alone.
  bool pressure_gradient_force = true;
  // The gas is solved every this many particle steps (the paper: 1), or sooner while it is fast:
  // a gas step whose CFL number would exceed 0.8 is taken early (Simulation::kGasCflTarget).
  int particle_steps_per_gas_step = 1;
  // The void fraction the gas and the drag see (eq 22): each cell's exact share of the spheres,
  // or those shares smoothed over a length (coupling/void_fraction_smoothing.hpp).
  VoidFraction void_fraction = VoidFraction::Exact;
  double void_fraction_length = 0.0;  // m, L of the smoothing; only with "smoothed"
};

// A point where the gas pressure is recorded (diagnostics.probes), inside the gas domain.
struct ProbePoint {
  double x = 0.0;  // m, from the left wall
  double y = 0.0;  // m, from the bottom
  bool operator==(const ProbePoint&) const = default;
};

struct DiagnosticsSettings {
  double output_interval = 1e-3;   // s, one timeseries row per interval
  double averaging_start = 1.0;    // s, tau_1 of eq 30; also where "after start-up" begins
  double overlap_limit = 0.2;      // overlap ratio treated as a runaway (the run fails)
  std::string save_state;          // write the final state here (relative to --out)
  // Pressure probes: each a timeseries column p_probe_N (N from 1), the gas pressure at the
  // point against the outlet's (run/recorder.hpp), and an entry of the summary's `probes`.
  std::vector<ProbePoint> probes;
};

// Bubble and slug analysis (`run --bubbles`; analysis/bubbles.hpp says how each is used).
// Lengths of 0 scale with the particle diameter d.
struct BubbleSection {
  double threshold = 0.8;       // void fraction above which a fine cell is void, in (0, 1)
  double min_diameter = 0.0;    // m, smallest equivalent diameter of a bubble (0: 2 d)
  double interval = 0.01;       // s, between analysed frames
  double slug_fraction = 0.6;   // a bubble wider than this share of the bed's width is a slug
  double cell_size = 0.0;       // m, fine grid of the void fraction (0: d / 2)
  double window = 0.0;          // m, side of the void fraction's sample window (0: 2.5 d)
  int min_track_frames = 3;     // frames a bubble must be seen in to count (shorter: flicker)
  double eruption_gap = 0.1;    // s, eruptions closer in time are one burst at the surface
  double slugging_min_fraction = 0.25;  // regime "slugging": share of frames with a slug
  double spouting_min_fraction = 0.5;   // regime "spouting": share of frames the jet is open
  double bed_min_fraction = 0.05;  // dense regions smaller than this share are splashes
};

struct Settings {
  SceneInfo scene;
  DomainSettings domain;
  ParticleSettings particles;
  ContactSettings contact;
  TimeSettings time;
  PhysicsSettings physics;
  GasSettings gas;
  InletSettings inlet;
  CouplingSettings coupling;
  DiagnosticsSettings diagnostics;
  BubbleSection bubbles;
  std::string source_dir = ".";  // folder of the scene file, for relative paths (not a TOML key)
  // The packed bed's state file for placement "packed" (not a TOML key). A Simulation never
  // makes it: the caller asks for it (run/packed_bed.hpp: prepare_packed_bed), which runs and
  // caches the packing when needed.
  std::string packed_state;
  // Threads inside a step (not a TOML key: the command line's --threads, default one per core).
  // 0: one per core. The library default is 1 so that tests and parallel sweeps never
  // oversubscribe the cores; results are the same bits for any count.
  int threads = 1;
  // An ensemble member's packing (`--seeds`, run/ensemble.hpp; not a TOML key): the lattice seed
  // of the packing this bed starts from, also when particles.packing_scene makes it (whose own
  // seed it then replaces). Unset: the packing scene's own seed.
  std::optional<std::uint64_t> packing_seed;
};

// v(key, field, info) for every field of a section, in file order: the one table of the scene's
// keys. The loader reads by it, the validator checks its ranges, the resolved-scene writer,
// `fluidbed keys` and the man page print it (info: unit, range, help; scene/field_info.hpp).
template <class V>
void visit_fields(SceneInfo& s, V&& v) {
  using namespace ranges;
  v("name", s.name, {"", any, "the scene's name, in titles and reports"});
  v("kind", s.kind, {"", any, "what the run measures on top of dp and overlaps"});
  v("description", s.description, {"", any, "free text about the scene"});
}
template <class V>
void visit_fields(DomainSettings& s, V&& v) {
  using namespace ranges;
  v("width", s.width, {"m", positive, "x extent of the bed (left wall at x = 0)"});
  v("height", s.height, {"m", positive, "y extent of the bed (bottom wall at y = 0)"});
  v("thickness", s.thickness, {"m", positive, "z extent of the slab, at least one diameter (thicker: particles move in 3D)"});
  v("top_wall", s.top_wall, {"", any, "a rigid wall at y = height (the paper's bed is open)"});
}
template <class V>
void visit_fields(ParticleSettings& s, V&& v) {
  using namespace ranges;
  v("count", s.count, {"", at_least(1), "number of spheres"});
  v("diameter", s.diameter, {"m", positive, "sphere diameter d"});
  v("density", s.density, {"kg/m^3", positive, "density of the spheres' material"});
  v("placement", s.placement, {"", any, "where the particles start"});
  v("seed", s.seed, {"", non_negative, "random numbers of the lattice placement"});
  v("fill_height", s.fill_height,
    {"m", non_negative, "lattice cells only below this height (0: the whole domain)"});
  v("x", s.x, {"m", any, "\"single\" placement: x of the particle"});
  v("y", s.y, {"m", any, "\"single\" placement: y of the particle"});
  v("vx", s.vx, {"m/s", any, "\"single\" placement: x velocity"});
  v("vy", s.vy, {"m/s", any, "\"single\" placement: y velocity"});
  v("spin", s.spin, {"rad/s", any, "\"single\" placement: angular velocity about z"});
  v("state_file", s.state_file,
    {"", any, "\"state\" placement: the state file, relative to the scene file"});
  v("packing_time", s.packing_time,
    {"s", positive, "\"packed\" placement: how long the lattice start falls"});
  v("packing_scene", s.packing_scene,
    {"", any, "\"packed\" placement: a scene that makes the packing instead (empty: this one)"});
  v("packing_friction", s.packing_friction,
    {"", non_negative, "\"packed\" placement: the packing's Coulomb friction (unset: contact.friction)"});
  v("packing_rolling_friction", s.packing_rolling_friction,
    {"", non_negative,
     "\"packed\" placement: the packing's rolling friction (unset: contact.rolling_friction)"});
  v("frozen", s.frozen, {"", any, "held in place: a fixed bed the gas flows through"});
}
template <class V>
void visit_fields(ContactSettings& s, V&& v) {
  using namespace ranges;
  v("stiffness", s.stiffness, {"N/m", positive, "normal spring constant kappa_n"});
  v("tangential_stiffness_ratio", s.tangential_stiffness_ratio,
    {"", non_negative, "kappa_t / kappa_n (the paper: 1)"});
  v("damping", s.damping, {"kg/s", non_negative, "normal damping coefficient eta_n"});
  v("tangential_damping_ratio", s.tangential_damping_ratio,
    {"", non_negative, "eta_t / eta_n (the paper: 1)"});
  v("friction", s.friction,
    {"", non_negative, "Coulomb friction gamma, particles (and walls unless wall_friction)"});
  v("wall_friction", s.wall_friction,
    {"", non_negative, "Coulomb friction gamma at the walls (unset: contact.friction)"});
  v("rolling_friction", s.rolling_friction,
    {"", non_negative,
     "rolling resistance mu_r: a torque mu_r R |F_n| against the relative rolling (0: none)"});
  v("displacement", s.displacement, {"", any, "how the contact displacements are found"});
  v("law", s.law, {"", any, "the contact's force law"});
  v("youngs_modulus", s.youngs_modulus,
    {"Pa", positive, "\"hertz_mindlin\": Young's modulus of the particles and walls"});
  v("poisson_ratio", s.poisson_ratio,
    {"", Range{0.0, 0.5, false, true}, "\"hertz_mindlin\": Poisson's ratio"});
  v("restitution", s.restitution,
    {"", Range{0.0, 1.0, true, false}, "\"hertz_mindlin\": restitution coefficient, pairs and walls"});
  // Beyond a few diameters the list holds pairs that cannot touch before the next rebuild: each
  // sphere gets about 2.7 (1 + skin)^2 candidates in a packed slab, so a skin of 10^5 makes every
  // pair a candidate and a step cost N^2. 10 diameters (some 330 candidates a sphere) is the most
  // the list takes; 0.3 to 0.8 measured equally fast.
  v("skin", s.skin,
    {"", Range{0.0, 10.0, false, false},
     "neighbour-list skin as a fraction of the largest diameter (speed only; at most 10)"});
  v("renumber_steps", s.renumber_steps,
    {"", at_least(-1), "steps between renumberings of the particles by cell (0: never; -1: "
                       "automatic, in large beds)"});
}
template <class V>
void visit_fields(TimeSettings& s, V&& v) {
  using namespace ranges;
  v("dt", s.dt, {"s", positive, "particle time step"});
  v("end", s.end, {"s", non_negative, "simulated time of a run (--until overrides it)"});
  v("integrator", s.integrator, {"", any, "the particles' time integrator"});
}
template <class V>
void visit_fields(PhysicsSettings& s, V&& v) {
  using namespace ranges;
  v("gravity", s.gravity, {"m/s^2", any, "gravitational acceleration along -y"});
}
template <class V>
void visit_fields(DiagnosticsSettings& s, V&& v) {
  using namespace ranges;
  v("output_interval", s.output_interval, {"s", positive, "one timeseries row per interval"});
  v("averaging_start", s.averaging_start,
    {"s", non_negative, "start of the means (tau_1 of eq 30) and of \"after start-up\""});
  v("overlap_limit", s.overlap_limit,
    {"", unit_fraction, "overlap ratio taken as a runaway: the run fails"});
  v("save_state", s.save_state,
    {"", any, "write the final state to this file, relative to --out (empty: none)"});
  v("probes", s.probes,
    {"m", any, "gas pressure probes [[x, y], ...]: a timeseries column p_probe_N each"});
}

template <class V>
void visit_fields(GasSettings& s, V&& v) {
  using namespace ranges;
  v("enabled", s.enabled, {"", any, "solve the gas (a [gas] section sets it unless it says false)"});
  v("density", s.density, {"kg/m^3", positive, "gas density (air)"});
  v("viscosity", s.viscosity, {"Pa s", positive, "gas dynamic viscosity (air)"});
  v("cells_x", s.cells_x, {"", at_least(3), "gas cells across the width (the paper: 10 mm)"});
  v("cells_y", s.cells_y, {"", at_least(3), "gas cells up the height (the paper: 20 mm)"});
  v("tolerance", s.tolerance, {"", positive, "SIMPLE: mass residual relative to the inflow"});
  v("max_iterations", s.max_iterations, {"", at_least(1), "SIMPLE iterations per gas step"});
  v("preconditioner_refresh", s.preconditioner_refresh,
    {"", non_negative, "pressure factorization rebuilt past this coefficient change (speed only)"});
}
template <class V>
void visit_fields(InletSettings& s, V&& v) {
  using namespace ranges;
  v("kind", s.kind, {"", any, "what the bottom of the bed lets in"});
  v("superficial_velocity", s.superficial_velocity,
    {"m/s", non_negative, "gas velocity U, the mean over the bottom"});
  v("jet_width", s.jet_width, {"m", positive, "width of each jet's slot"});
  v("jets", s.jets, {"", at_least(1), "jet slots, one every width / jets"});
  v("plenum_height", s.plenum_height,
    {"m", non_negative, "gas below the particles' floor, which it crosses freely (0: none)"});
  v("distributor_resistance", s.distributor_resistance,
    {"Pa s/m", non_negative,
     "with a plenum: a plate at the floor whose pressure drop is this times the superficial "
     "velocity through it (0: none)"});
}
template <class V>
void visit_fields(CouplingSettings& s, V&& v) {
  using namespace ranges;
  v("pressure_gradient_force", s.pressure_gradient_force,
    {"", any, "model A: particles feel -V grad p besides drag (false: the paper's printed form)"});
  v("particle_steps_per_gas_step", s.particle_steps_per_gas_step,
    {"", at_least(1), "the gas is solved every this many particle steps (or sooner, by CFL)"});
  v("void_fraction", s.void_fraction, {"", any, "how the gas cells' void fraction is found"});
  v("void_fraction_length", s.void_fraction_length,
    {"m", non_negative, "\"smoothed\" void fraction: the smoothing length L (0 with \"exact\")"});
}

template <class V>
void visit_fields(BubbleSection& s, V&& v) {
  using namespace ranges;
  v("threshold", s.threshold, {"", open_unit, "void fraction above which a fine cell is void"});
  v("min_diameter", s.min_diameter,
    {"m", non_negative, "smallest equivalent diameter of a bubble (0: 2 d)"});
  v("interval", s.interval, {"s", positive, "simulated time between analysed frames"});
  v("slug_fraction", s.slug_fraction,
    {"", unit_fraction, "a bubble wider than this share of the bed is a slug"});
  v("cell_size", s.cell_size, {"m", non_negative, "fine grid of the void fraction (0: d / 2)"});
  v("window", s.window, {"m", non_negative, "side of the void fraction's sample window (0: 2.5 d)"});
  v("min_track_frames", s.min_track_frames,
    {"", at_least(1), "frames a bubble must be seen in to count (fewer: flicker)"});
  v("eruption_gap", s.eruption_gap,
    {"s", non_negative, "eruptions closer in time are one burst at the surface"});
  v("slugging_min_fraction", s.slugging_min_fraction,
    {"", unit_fraction, "regime \"slugging\": least share of frames with a slug"});
  v("spouting_min_fraction", s.spouting_min_fraction,
    {"", unit_fraction, "regime \"spouting\": least share of frames the jet is open to the top"});
  v("bed_min_fraction", s.bed_min_fraction,
    {"", below_one, "dense regions smaller than this share of the bed are splashes"});
}

// v(section_name, section_struct) for every section.
template <class V>
void visit_sections(Settings& s, V&& v) {
  v("scene", s.scene);
  v("domain", s.domain);
  v("particles", s.particles);
  v("contact", s.contact);
  v("time", s.time);
  v("physics", s.physics);
  v("gas", s.gas);
  v("inlet", s.inlet);
  v("coupling", s.coupling);
  v("diagnostics", s.diagnostics);
  v("bubbles", s.bubbles);
}

}  // namespace fluidbed
