#pragma once
// The viewer's engine side: the simulation the panel controls (ViewModel, no threads) and the
// thread that steps it (ViewEngine). The engine thread owns the model; the main thread sees it
// only through snapshots (SnapshotChannel: newest wins, the engine never waits for the screen),
// a status copied under a short lock, and plot samples it drains. Panel edits travel the other
// way through a CommandQueue and are applied between steps. No lock is held while stepping.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

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

// Commands from the main thread to the engine thread, in order.
class CommandQueue {
 public:
  void push(const ViewCommand& c);
  // Everything queued so far (in order); waits up to `wait` for the first when the queue is empty.
  std::vector<ViewCommand> take(std::chrono::milliseconds wait);
  // Wakes a waiting take() (to stop the thread).
  void wake();

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<ViewCommand> queue_;
  bool woken_ = false;
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
  // not) is kept; the gas velocity is part of the state and returns to the scene's.
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

// What the panel shows beside the picture (copied under a short lock).
struct EngineStatus {
  bool stepping = false;  // running, or single steps / a run_until pending
  bool running = false;   // the run/pause switch
  double time = 0.0;      // s, of the last published snapshot
  std::int64_t steps = 0;
  double sim_s_per_wall_s = 0.0;  // measured over the last quarter second of stepping
  double steps_per_s = 0.0;
  std::size_t particles = 0;
  double superficial_velocity = 0.0;  // m/s, the inlet setting
  double jet_velocity = 0.0;          // m/s, that setting through the slot
  double inlet_jet_velocity = 0.0;    // m/s, what the gas used at its last step
  bool ideal = false;
  double stiffness = 0.0;        // N/m, in use
  double run_until = -1.0;       // s: a script's `at T` on its way there (< 0: none)
  std::uint64_t generation = 0;  // resets so far (the plots start again)
  std::uint64_t commands_applied = 0;
  std::uint64_t state_hash = 0;  // of the state where the engine last stopped
  std::uint64_t start_hash = 0;
  // A SimulationFailure (with what to do in the viewer) or a refused command: stepping stops
  // until Reset, which leaves the run/pause switch as it is (a failure does not touch it).
  std::string error;
  std::string refusal;  // the last command refused (a stiffness the step cannot take), one line
  CurveState curve;     // the live Fig. 6
  std::shared_ptr<const BubbleView> bubbles;  // the last bubble analysis (regime, outlines)
};

// What the viewer says after a SimulationFailure: the failure in words, what it means for the
// bed, and what to do in the viewer (lower the gas, Reset), instead of the engine's advice for
// scene files (a shorter time step, which the viewer cannot change).
std::string failure_in_the_viewer(const std::string& what, double superficial_velocity);

class ViewEngine {
 public:
  struct Options {
    double publish_interval = 0.005;  // wall s: the newest state is published at least this often
    bool start_running = true;
    double settle = 0.5;   // s, the live curve's settling time (as sweep's averaging start)
    double average = 1.0;  // s, its averaging window
  };
  ViewEngine(const Settings& scene, Options options);
  ~ViewEngine();  // stops the thread
  ViewEngine(const ViewEngine&) = delete;
  ViewEngine& operator=(const ViewEngine&) = delete;

  void start();
  void stop();
  const Options& options() const { return options_; }
  // Queues a command; returns how many have been posted so far (compare commands_applied).
  std::uint64_t post(const ViewCommand& c);
  const SnapshotChannel& snapshots() const { return channel_; }
  EngineStatus status() const;
  // The plot samples recorded since the last call (oldest first).
  std::vector<PlotSample> take_samples();
  // Waits (up to `timeout`) until every posted command was applied and the engine stopped
  // stepping; true when it did.
  bool wait_until_stopped(std::chrono::milliseconds timeout) const;

 private:
  void loop();
  void apply(const ViewCommand& c);
  void publish();
  void add_bubbles(Snapshot& snap) const;
  void sample_after_step();
  void measure_speed(bool stopping);
  double held_velocity() const;  // m/s, the inlet setting
  void stopped();                // the engine just stopped stepping: publish the state and its hash

  ViewModel model_;
  Options options_;
  CommandQueue queue_;
  SnapshotChannel channel_;
  std::atomic<bool> quit_{false};
  std::atomic<std::uint64_t> posted_{0};
  std::thread thread_;

  // Engine thread only.
  bool running_ = false;
  std::int64_t steps_left_ = 0;
  std::int64_t until_step_ = -1;
  std::uint64_t applied_ = 0, generation_ = 0;
  std::string error_, refusal_;
  double sample_interval_ = 1e-3;
  double next_sample_ = 0.0;
  double interval_overlap_ = 0.0;
  std::chrono::steady_clock::time_point last_publish_{}, speed_t0_{};
  std::int64_t speed_steps0_ = 0;
  // Stepping spans shorter than the speed's quarter second (a script's `at T` lines) are summed
  // until they make one.
  double speed_span_s_ = 0.0;
  std::int64_t speed_span_steps_ = 0;
  double sim_s_per_wall_s_ = 0.0, steps_per_s_ = 0.0;
  LiveCurve curve_;
  // The bubble analysis every [bubbles] interval: the regime in words, the outlines
  // (ViewCommand::bubbles puts them into the snapshots) and the bubble under the pointer. A
  // reset or a new contact law starts its tracking again.
  RegimeWatch regime_;
  bool bubbles_on_ = false;

  mutable std::mutex status_mutex_;
  mutable std::condition_variable status_changed_;
  EngineStatus status_;
  std::vector<PlotSample> samples_;  // under status_mutex_
};

}  // namespace fluidbed::app
