#pragma once
// The view session: the simulation the panel controls (ViewModel), the live Fig. 6 it builds
// (view/live_curve), the regime watch (view/regime_watch) and the plot samples, changed by the
// viewer's commands between steps and measured after each step. One piece for both viewers: the
// window's engine thread (view/engine.hpp) owns one and adds the thread, the run/pause switch
// and the publishing; the headless viewer (view/headless.hpp) owns one and adds the script's
// clock and the pictures. No threads, no locks: whoever owns it is the only one to touch it.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

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
  };
  Kind kind = Kind::pause;
  double value = 0.0;
};

// The scene with the viewer's contact choices: the ideal case (damping and friction 0) and a
// stiffness (N/m, 0: the scene's) with the damping scaled by sqrt(k / k_scene), which keeps the
// restitution. InputError when the scene's time step is too long for that stiffness (the
// refusals of sim/checks.hpp).
Settings with_contact(const Settings& scene, bool ideal, double stiffness);

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
  const Settings& scene() const { return scene_; }
  std::uint64_t start_hash() const { return start_hash_; }
  // The gas's face velocity at the inlet, largest over the bottom row (m/s): the jet the gas
  // actually felt at its last step (0 without gas).
  double inlet_jet_velocity() const;

 private:
  std::unique_ptr<Simulation> build() const;

  Settings scene_;
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

  // A command that changes the bed or what is measured of it: reset (to the packed bed at the
  // velocity held now; after a failure at it, at the safe velocity), velocity, ideal,
  // stiffness, bubbles, settle, average. The stepping commands (run, pause, step, run_until)
  // are the owner's and change nothing here. InputError for a refused value (the bed goes on as
  // it was); another exception when rebuilding the solvers failed.
  void apply(const ViewCommand& c);
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
  void watch_the_top();
};

}  // namespace fluidbed::app
