#pragma once
// The view session: the simulation the panel controls (ViewModel), the live Fig. 6 it builds
// (view/live_curve), the regime watch (view/regime_watch) and the plot samples, changed by the
// viewer's commands between steps and measured after each step. One piece for both viewers: the
// window's engine thread (view/engine.hpp) owns one and adds the thread, the run/pause switch
// and the publishing; the headless viewer (view/headless.hpp) owns one and adds the script's
// clock and the pictures. No threads, no locks: whoever owns it is the only one to touch it.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "run/umf_estimate.hpp"
#include "scene/settings.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot.hpp"
#include "view/live_curve.hpp"
#include "view/regime_watch.hpp"

namespace fluidbed::app {

// What the panel, the keyboard and scripts ask of the engine.
struct ViewCommand {
  enum class Kind {
    run,        // step continuously
    pause,      // stop stepping (simulated time stops)
    step,       // `value` single steps, then pause
    run_until,  // step to the step nearest simulated time `value` (s), then pause
    reset,      // back to the starting (packed) state, bit for bit
    velocity,   // superficial gas velocity `value` (m/s) from the next gas step on
    ideal,      // `value` != 0: contact damping 0 and friction 0 (the paper's ideal case)
    stiffness,  // contact stiffness `value` (N/m; 0: the scene's), damping scaled to keep e
    bubbles,    // `value` != 0: the snapshots carry the bubble outlines and the fine void fraction
    settle,     // the live curve's settling time `value` (s of simulated time)
    average,    // the live curve's averaging window `value` (s of simulated time)
    particles,  // spheres of diameter `value` (m) and `density` (kg/m^3), 0 and 0: the scene's
  };
  Kind kind = Kind::pause;
  double value = 0.0;
  double density = 0.0;  // particles only
};

// The scene with the viewer's contact choices: the ideal case (damping and friction 0) and a
// stiffness (N/m, 0: the scene's) with the damping scaled by sqrt(k / k_scene), which keeps the
// restitution. InputError when the scene's time step is too long for that stiffness (the
// refusals of sim/checks.hpp).
Settings with_contact(const Settings& scene, bool ideal, double stiffness);

// The scene with other spheres (the viewer's live change): diameter d (m) and density rho
// (kg/m^3), the count kept, the step set by the scene's rule from the new contact duration. The
// scene's step is a share of its contact duration, and so is the new one: with mass ratio
// r = (rho / rho_0) (d / d_0)^3, the linear law's duration pi sqrt(m / kappa) (kappa kept) and
// its damping for the same restitution both scale by sqrt(r); Hertz's duration, proportional to
// m^(2/5) R^(-1/5) for the same material and impact speed, by r^(2/5) (d / d_0)^(-1/5). The gas
// step stays at most the scene's (its CFL and coupling were measured for it): the particle step
// at most that, and as many of them in a gas step as fit. A
// monolayer's slab stays one sphere thick; the fill height of a lattice start scales with the
// spheres' area, (d / d_0)^2. The new bed is packed with the scene's own contacts (not the
// packing scene's, which packs other particles): at the scene's own spheres the teaching bed
// packed that way stands 0.3 % taller than from the paper's packing, in a fifth of the time.
// InputError for an impossible value or a bed the scene's checks refuse.
Settings with_particles(const Settings& scene, double diameter, double density);

// The simulation the viewer controls. The starting state is saved once (in a private temporary
// folder) so that reset restores it exactly; a change of the contact law (the ideal case, the
// stiffness) rebuilds the solvers from the settings and carries the whole state across bit for
// bit.
class ViewModel {
 public:
  // Builds the scene (may make and cache its packed bed). InputError for a bad scene.
  explicit ViewModel(const Settings& scene);
  ~ViewModel();
  ViewModel(const ViewModel&) = delete;
  ViewModel& operator=(const ViewModel&) = delete;

  Simulation& sim() { return *sim_; }
  const Simulation& sim() const { return *sim_; }
  // Back to the starting state: the same state hash as at the start. The model choice (ideal or
  // not) is kept; the gas velocity is part of the state and returns to the scene's (the session
  // then sets the one the teacher chose, ViewSession::apply).
  void reset();
  void set_velocity(double u);  // m/s, clamped to >= 0
  void set_ideal(bool on);
  bool ideal() const { return ideal_; }
  void set_stiffness(double k);  // N/m, 0: the scene's; InputError when the step is too long
  double stiffness() const;      // N/m, in use
  // Other spheres (with_particles; 0 and 0, or the scene's own values: the scene's): a packed bed
  // of them (packed once, then cached) becomes the starting state, and the bed starts from it.
  // The ideal case and the stiffness are kept. InputError (nothing changed) for refused values.
  void set_particles(double diameter, double density,
                     const std::function<void(const std::string&)>& notify = {});
  // The scene the bed runs now (the particles changed or not), and the one it was opened with.
  const Settings& scene() const { return scene_; }
  const Settings& opened_scene() const { return opened_; }
  std::uint64_t start_hash() const { return start_hash_; }
  // The gas's face velocity at the inlet, largest over the bottom row (m/s): the jet the gas
  // actually felt at its last step (0 without gas).
  double inlet_jet_velocity() const;

 private:
  std::unique_ptr<Simulation> build() const;
  void save_start(const Settings& scene);  // its starting state into start_file_

  Settings opened_;  // the scene as opened
  Settings scene_;   // with the particles in use
  std::string dir_;         // private temporary folder (removed by the destructor)
  std::string start_file_;  // the starting state
  std::unique_ptr<Simulation> sim_;
  std::uint64_t start_hash_ = 0;
  bool ideal_ = false;
  double stiffness_ = 0.0;  // N/m, 0: the scene's
  void rebuild_keeping_state(bool ideal, double stiffness);
};

// One point of the panel's plots, every diagnostics.output_interval of simulated time.
struct PlotSample {
  double t = 0.0;            // s
  double dp = 0.0;           // Pa
  double max_overlap = 0.0;  // largest overlap ratio over the interval
};

class ViewSession {
 public:
  // The live curve's settling time and averaging window (s of simulated time), as sweep's
  // averaging start and window.
  static constexpr double kSettle = 0.5, kAverage = 1.0;

  // Builds the model (ViewModel's InputError for a bad scene); `settle` and `average` are the
  // live curve's times.
  explicit ViewSession(const Settings& scene, double settle = kSettle, double average = kAverage);

  // The scene's measured U_mf (the presets' and the slider's; umf 0: not measured) and the
  // folder of shipped answers: a change of the particles scales it (umf_for_particles).
  void set_umf(const UmfEstimate& scene_umf, const std::string& shipped);
  // For the particles in use: the scene's, or scaled for the new ones (umf 0: not known).
  const UmfEstimate& umf() const { return umf_; }
  // Changes of the particles so far (the window takes the new U_mf and step when it moves).
  std::uint64_t particles_changes() const { return particles_changes_; }

  // A command that changes the bed or what is measured of it: reset (to the packed bed at the
  // velocity held now; after a failure at it, at the safe velocity), velocity, ideal,
  // stiffness, bubbles, settle, average, particles (a packed bed of the new spheres at the
  // velocity held now; the curve and the regime start again, U_mf follows; seconds of work, and
  // `notify` hears what is being done). The stepping commands (run, pause, step, run_until)
  // are the owner's and change nothing here. InputError for a refused value (the bed goes on as
  // it was); another exception when rebuilding the solvers failed.
  void apply(const ViewCommand& c, const std::function<void(const std::string&)>& notify = {});
  // One step, then what is measured after it: the regime watch, and every output interval of
  // simulated time the live curve's sample (beds with gas) and a plot sample, returned. A
  // SimulationFailure of the step is the caller's (nothing is measured then).
  std::optional<PlotSample> step();
  // The state into `snap`, with the bubble outlines and the fine void fraction while the
  // bubbles are on (a snapshot from a pool comes back with its old fields: they are cleared).
  void snapshot(Snapshot& snap) const;

  Simulation& sim() { return model_.sim(); }
  const Simulation& sim() const { return model_.sim(); }
  const ViewModel& model() const { return model_; }
  const CurveState& curve() const { return curve_.state(); }
  // The last bubble analysis (the regime, the outlines; null before the first).
  std::shared_ptr<const BubbleView> bubbles() const { return regime_.view(); }
  double held_velocity() const;  // m/s, the inlet setting (0 without gas)
  // The last velocity the bed ran at for kSafeSteps steps or more before the velocity was changed
  // (m/s, < 0: none yet): after a failure at the velocity held now, Reset returns to it.
  double safe_velocity() const { return safe_velocity_; }
  // The step just taken failed (SimulationFailure): Reset starts from the packed bed at the safe
  // velocity unless the velocity is changed first.
  void failed() { failed_velocity_ = held_velocity(); }
  static constexpr int kSafeSteps = 10;
  // Spheres the gas holds against the top screen (a scene with domain.top_wall): how many touch
  // it now when some have touched it without a break for kHeldAtTop of simulated time, else 0.
  // A bed blown against the screen is not fluidized: its dp is the screen's push.
  int held_at_top() const { return held_at_top_; }
  static constexpr double kHeldAtTop = 1.0;  // s

 private:
  ViewModel model_;
  LiveCurve curve_;
  // The bubble analysis every [bubbles] interval: the regime in words, the outlines
  // (ViewCommand::bubbles puts them into the snapshots) and the bubble under the pointer. A
  // reset starts its tracking again.
  RegimeWatch regime_;
  bool bubbles_on_ = false;
  double sample_interval_ = 1e-3;  // s of simulated time between plot samples
  double next_sample_ = 0.0;       // s
  double interval_overlap_ = 0.0;  // largest overlap ratio since the last sample
  double safe_velocity_ = -1.0;    // m/s, see safe_velocity()
  double failed_velocity_ = -1.0;  // m/s, the velocity of the last failure (< 0: none since reset)
  int steps_at_velocity_ = 0;      // steps since the velocity was last set
  double at_top_since_ = -1.0;     // s, since when spheres touch the top screen (< 0: none now)
  int held_at_top_ = 0;
  UmfEstimate scene_umf_, umf_;
  std::string umf_shipped_;
  std::uint64_t particles_changes_ = 0;
  void watch_the_top();
  void start_again();  // the bookkeeping of a new start (reset, new particles)
};

}  // namespace fluidbed::app
