#pragma once
// The particle model: neighbour search, contacts with history, walls, gravity and the time
// integrators (the paper's Newmark predictor-corrector, velocity Verlet, symplectic Euler).
// Forces from the gas come in through Particles::ext_fx/ext_fy and are held over a step.
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "core/permute.hpp"
#include "core/phase_timer.hpp"
#include "dem/contact_history.hpp"
#include "dem/contact_law.hpp"
#include "dem/integrators.hpp"
#include "dem/neighbour_list.hpp"
#include "dem/particles.hpp"
#include "dem/walls.hpp"

namespace fluidbed {

// What the particle model needs from a scene, built once from the settings
// (sim/model_params.hpp: dem_params_for).
struct DemParams {
  ContactParams contact;          // eqs 3-7
  std::optional<double> wall_mu;  // friction at the walls; unset: contact.mu
  bool incremental = true;        // eqs 13-17; false: the geometric overlap
  Integrator integrator = Integrator::Newmark;
  double dt = 1.5e-5;                 // s
  double gravity = 9.81;              // m/s^2, along -y
  double width = 0.15, height = 0.9;  // m, the box the particles must stay in
  double thickness = 0.004;           // m, the slab (a thick slab's particles stay in it too)
  std::vector<Wall> walls;            // the slab's planar walls (dem/walls.hpp)
  double skin = 0.4;                  // neighbour-list skin, fraction of the largest diameter
  double overlap_limit = 0.2;         // overlap ratio treated as a runaway
  bool frozen = false;                // a fixed bed: nothing moves
  int threads = 1;                    // inside a step; 0: one per core
  // Steps between renumberings of the particles by cell (0: never): see DemSolver::renumber.
  int renumber_steps = 0;
};

// Everything that defines where a run is: saved and loaded bit-exactly. The pair history lives
// in the solver's neighbour list while it runs; `pairs` holds it only when exported (state files)
// or about to be imported (set_state).
//
// An exported state (and a state file) is in the particles' ids: particle k of the arrays, the
// pairs and the walls is the one placed k-th, whatever order the solver keeps them in. `order`
// is that order (the id at each of the solver's places; empty: the ids' own), so that a state
// loaded continues with the same bits.
struct DemState {
  Particles particles;
  PairContacts pairs;
  WallHistory walls;
  double time = 0.0;  // s
  std::int64_t step = 0;
  std::vector<std::int32_t> order;
};

// Measured at every step.
struct StepDiagnostics {
  double max_overlap_ratio = 0.0;       // pairs: 1 - L / (R_i + R_j) (the paper's Fig. 15)
  double max_wall_overlap_ratio = 0.0;  // walls: 1 - distance / R_i
  int pair_contacts = 0;
  int wall_contacts = 0;
  int sliding_contacts = 0;
  double kinetic_energy = 0.0;  // J, translation and rotation
};

// The work of the forces that the mechanical energy does not hold, summed step by step since the
// solver was built: each force's power at the velocities the contact law saw, times dt. With the
// kinetic, potential and spring energies of the state (analysis/energy_budget.hpp) it closes the
// particles' energy budget; what it leaves over is the integration error.
struct EnergyLedger {
  // J, done on the particles by the gas (ext_fx, ext_fy: drag, pressure gradient)
  double gas_work = 0.0;
  double dashpot = 0.0;   // J, dissipated by the normal and tangential dashpots (>= 0)
  double friction = 0.0;  // J, dissipated by sliding contacts (>= 0)
  EnergyLedger& operator+=(const EnergyLedger& o) {
    gas_work += o.gas_work;
    dashpot += o.dashpot;
    friction += o.friction;
    return *this;
  }
};

// The energy stored in the contacts' springs, from their displacement history (J): 1/2 kappa_n
// delta_n^2 in compression and 1/2 kappa_t delta_t^2, pairs and walls.
struct SpringEnergy {
  double normal = 0.0;
  double tangential = 0.0;
};

class DemSolver {
 public:
  // Takes the particles (placed, with mass properties) and builds the grid and history.
  DemSolver(const DemParams& params, Particles particles);

  // Work of another part of the model on each thread's particles [b, e), run inside the step's
  // parallel region once the particles have moved (the coupler's drag update), so that a step
  // forks its threads once.
  using RangeWork = std::function<void(std::size_t b, std::size_t e)>;

  // One time step of dt, then `after` (may be empty) on every particle. Throws
  // SimulationFailure when the state stops making sense.
  void step(const RangeWork& after = {});

  // The live state; its `pairs` member is not kept current while running (see exported_state).
  const DemState& state() const { return state_; }
  DemState& state() { return state_; }
  // A complete copy, pair history included (for state files).
  DemState exported_state() const;
  // Threads used inside a step (1: none); results are the same bits for any count.
  int threads() const { return threads_; }
  // Thread t's particles [b, e) of T threads in the last step's split (whole blocks, balanced
  // by work at each neighbour-list rebuild). Other per-particle loops use it too, so each
  // particle's data stays on one core.
  void thread_range(int t, int T, std::size_t& b, std::size_t& e) const;
  const std::vector<std::size_t>& split() const { return split_; }
  const NeighbourList& neighbours() const { return list_; }
  const Particles& particles() const { return state_.particles; }
  Particles& particles() { return state_.particles; }
  double time() const { return state_.time; }
  double dt() const { return dt_; }
  const StepDiagnostics& diagnostics() const { return diag_; }
  const std::vector<Wall>& walls() const { return walls_; }
  const ContactParams& contact_params() const { return params_; }
  // Largest overlap ratio of each particle's contacts at the last force evaluation (pairs:
  // 1 - L / (R_i + R_j); walls: 1 - distance / R_i, halved to the same scale).
  const std::vector<double>& particle_overlap() const { return overlap_; }
  // The energy ledger since construction, and the springs' energy now.
  const EnergyLedger& energy_ledger() const { return ledger_; }
  // A run resumed from a checkpoint (run/checkpoint.hpp) carries on its ledger, not a new one.
  void set_energy_ledger(const EnergyLedger& l) { ledger_ = l; }
  SpringEnergy spring_energy() const;

  // Replaces the state (an exported one or a loaded file, in ids, its pair history included); the
  // particle count must match.
  void set_state(DemState s);

  // The particles' numbering. The solver keeps its arrays in an order of its own (particles(),
  // state(), every per-particle vector it hands out): with renumber_steps, every so many steps it
  // sorts them by neighbour cell (dem/renumber.cpp), so that a contact's two particles sit close
  // in memory however the bed has mixed. Each particle keeps its id (the place it was given);
  // everything that names a particle to a user - tracks, pictures, files, messages - uses ids.
  bool renumbered() const { return !id_.empty(); }
  // The id of the particle at place s, and the place of particle `id`.
  std::size_t id_of(std::size_t s) const {
    return id_.empty() ? s : static_cast<std::size_t>(id_[s]);
  }
  std::size_t place_of(std::size_t id) const {
    return id_.empty() ? id : static_cast<std::size_t>(place_[id]);
  }
  // The id at each place and the place of each id (both empty while they are the same).
  const std::vector<std::int32_t>& ids() const { return id_; }
  const std::vector<std::int32_t>& places() const { return place_; }
  // A per-particle vector of the solver's order in id order, and back (core/permute.hpp).
  template <class T>
  void to_ids(const std::vector<T>& v, std::vector<T>& out) const {
    if (id_.empty() || v.size() != id_.size()) {
      out = v;
      return;
    }
    out.resize(v.size());  // one pass: out[k] = v[place of id k]
    for (std::size_t k = 0; k < v.size(); ++k) out[k] = v[static_cast<std::size_t>(place_[k])];
  }
  template <class T>
  void to_places(std::vector<T>& v) const {
    if (!id_.empty() && v.size() == id_.size()) gather_by(v, id_);
  }
  // Called with the new order (from[s]: the place the particle now at s came from) each time the
  // solver renumbers, so that per-particle data kept elsewhere (the coupler's) follows.
  using Renumbered = std::function<void(const std::vector<std::int32_t>& from)>;
  void on_renumber(Renumbered f) { on_renumber_ = std::move(f); }
  // Time spent per phase since construction (or reset), for the benchmark's split.
  PhaseTimes& phase_times() const { return times_; }

  std::uint64_t state_hash() const;
  // The particles' configuration alone (positions, velocities, spins, contact history), without
  // the clock: equal when one run hands its particles to the next.
  std::uint64_t configuration_hash() const;

 private:
  // One thread's share of a step's diagnostics (padded: threads write their own).
  struct alignas(64) StepPartial {
    int contacts = 0, sliding = 0, wall_contacts = 0;
    double max_ratio = 0.0, max_wall_ratio = 0.0;
    double moved2[2] = {0.0, 0.0};  // m^2, two largest squared displacements since the build
    std::int64_t k0 = 0;            // the thread's first candidate slot
    std::int64_t worst = -1;        // the first slot with the largest pair overlap (-1: none)
    bool outside = false;
  };
  template <bool Incremental>
  void step_particles(const RangeWork& after);
  template <bool Incremental>
  void pair_pass(int t, std::size_t e, double dtau, StepPartial& acc);
  template <bool Incremental>
  bool particle_pass(int t, std::size_t b, std::size_t e, double dtau, StepPartial& acc);
  // The same two passes in three dimensions (a thick slab: dem/depth_passes.cpp).
  void pair_pass_depth(int t, std::size_t e, double dtau, bool incremental, StepPartial& acc);
  bool particle_pass_depth(int t, std::size_t b, std::size_t e, double dtau, bool incremental,
                           StepPartial& acc);
  // The end of a particle pass over [b, e): the integrator's part after the forces, each block's
  // kinetic energy and the box check (true: a particle left it), the walls' counts into acc.
  bool finish_particle_pass(std::size_t b, std::size_t e, int wall_contacts, int sliding,
                            double max_wall_ratio, StepPartial& acc);
  void before_forces(std::size_t b, std::size_t e);
  bool after_forces(std::size_t blk, std::size_t i0, std::size_t i1);
  void finish_step();
  void balance(int threads);
  [[noreturn]] void fail(const std::string& what) const;
  // dem/renumber.cpp: the particles sorted by cell (at the start of a step, every
  // renumber_steps_), and the conversions between the solver's order and the ids.
  void renumber();
  void reorder(const std::vector<std::int32_t>& from);

  DemState state_;
  NeighbourList list_;
  std::vector<Wall> walls_;
  ContactParams params_;
  ContactParams wall_params_;  // params_ with the walls' friction
  Integrator integrator_;
  bool incremental_;
  bool frozen_;
  double dt_;
  double gravity_;
  double width_, height_, thickness_;
  bool depth_ = false;             // the particles move in three dimensions (Particles::has_depth)
  std::vector<int> planar_walls_;  // the walls with nz = 0, ascending
  std::vector<int> depth_walls_;   // the front and back walls (a thick slab), ascending
  double overlap_limit_;
  int threads_ = 1;
  bool parallel_ = false;  // threads_ > 1 and enough particles to pay for a fork
  StepDiagnostics diag_;
  std::vector<double> overlap_;
  double skin_ = 0.0;  // m, of the neighbour list
  // Per thread, its particles that can touch a wall before the next neighbour-list build,
  // ascending: within R + skin of a wall at the build (they move less than the skin until the
  // next), or touching one then (so that its history is cleared when they part).
  std::vector<std::vector<std::int32_t>> near_wall_;
  int near_threads_ = 0;  // the thread count near_wall_ was made for (0: none)
  void find_near_wall(std::vector<std::int32_t>& out, std::size_t b, std::size_t e) const;
  // Rebuilds the neighbour list and what depends on it (the wall candidates): called by each of
  // the T threads of the step with its particles [b, e), or by one (t = 0, T = 1) outside.
  void rebuild(int t, int T, std::size_t b, std::size_t e);
  mutable PhaseTimes times_;
  std::vector<StepPartial> partial_;  // per thread
  // A contact's force as passed to the thread that holds its second particle j.
  struct Push {
    double fx, fy, ft, ratio;
    std::int32_t j;
    double roll;  // rolling resistance torque on i (-roll on j); 0 without it
  };
  std::vector<std::vector<Push>> passed_;  // per thread: its contacts with j beyond its range
  struct PushDepth {                       // a thick slab's further components of the same contacts
    double fz, ftx, fty, roll_x, roll_y;
  };
  std::vector<std::vector<PushDepth>> passed_depth_;
  // A thick slab's wall contacts, per thread, listed and computed kWallChunk at a time
  // (particle_pass_depth), and the walls as the kernel reads them.
  static constexpr std::int64_t kWallChunk = 256;
  // The front and back walls' scan (particle_pass_depth): spheres at a time, walls at most.
  static constexpr std::size_t kWallScan = 256, kDepthWalls = 2;
  struct WallChunk {
    std::vector<std::int32_t> on, particle;
    ContactScratch out;
  };
  std::vector<WallChunk> wall_chunks_;
  std::vector<double> wall_nx_, wall_ny_, wall_nz_, wall_offset_;
  // balance(): per thread, the time spent on its own particles since the last balance (padded:
  // each thread writes its own), its measured speed (work units per second, smoothed) and the
  // work of its range.
  struct alignas(64) ThreadClock {
    double seconds = 0.0;
  };
  std::vector<ThreadClock> busy_;
  std::vector<double> speed_, work_;
  std::int64_t steps_since_balance_ = 0;
  std::vector<double> block_ke_;  // J, per block of particles (core/threads.hpp)
  // The step's energy ledger per block of particles (a pair counts in its first particle's
  // block), summed in block order: the same bits for any thread count.
  std::vector<EnergyLedger> block_ledger_;
  EnergyLedger ledger_;
  bool outside_ = false;            // a particle left the box in the last step
  std::vector<std::size_t> split_;  // thread t's particles: [split_[t], split_[t + 1])
  int worst_pair_i_ = -1, worst_pair_j_ = -1;
  int renumber_steps_ = 0;
  double cell_ = 0.0;  // m, the cells of renumber's sort
  // The id at each place and the place of each id (empty while they are the same).
  std::vector<std::int32_t> id_, place_;
  Renumbered on_renumber_;
};

// Binary state files: magic, version, counts, then raw arrays (bit-exact restart).
void write_state(std::ostream& out, const DemState& s);
DemState read_state(std::istream& in, const std::string& origin);
void save_state_file(const std::string& path, const DemState& s);
DemState load_state_file(const std::string& path);

}  // namespace fluidbed
