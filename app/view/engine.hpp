#pragma once
// The viewer's engine side: the thread (ViewEngine) that steps the view session
// (view/session.hpp: the simulation the panel controls, the live curve, the regime; no threads).
// The engine thread owns the session; the main thread sees it
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
#include "sim/snapshot.hpp"
#include "view/session.hpp"

namespace fluidbed::app {

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
  double stiffness = 0.0;        // N/m, in use (0: Hertz-Mindlin contacts)
  double run_until = -1.0;       // s: a script's `at T` on its way there (< 0: none)
  std::uint64_t generation = 0;  // resets so far (the plots start again)
  std::uint64_t commands_applied = 0;
  std::uint64_t state_hash = 0;  // of the state where the engine last stopped
  std::uint64_t start_hash = 0;
  // A SimulationFailure (with what to do in the viewer) or a refused command: stepping stops
  // until Reset, which leaves the run/pause switch as it is (a failure does not touch it).
  std::string error;
  std::string error_plain;  // the same for a class (the presenter mode): no engine's words
  std::string refusal;  // the last command refused (a stiffness the step cannot take), one line
  int held_at_top = 0;  // spheres the gas holds against the top screen (ViewSession::held_at_top)
  CurveState curve;     // the live Fig. 6
  // The spheres in use (m, kg/m^3), the particle step (s) and the U_mf for them (ViewSession's;
  // umf 0: not known), changed by the particles command (particles_changes counts the changes).
  double particle_diameter = 0.0, particle_density = 0.0, dt = 0.0;
  double umf = 0.0;
  bool umf_cached = false;
  std::string umf_method, umf_method_short;
  std::uint64_t particles_changes = 0;
  // Work that holds the bed for seconds (a new packed bed): what is being done; empty: none.
  std::string busy;
  std::shared_ptr<const BubbleView> bubbles;  // the last bubble analysis (regime, outlines)
};

// What the viewer says after a SimulationFailure: the failure in words, what it means for the
// bed, and what to do in the viewer (lower the gas, Reset), instead of the engine's advice for
// scene files (a shorter time step, which the viewer cannot change). `safe_velocity` (m/s) is
// the last velocity the bed ran at before it (ViewSession::safe_velocity, < 0: none), the one
// Reset then returns to.
std::string failure_in_the_viewer(const std::string& what, double superficial_velocity,
                                  double safe_velocity);
// The same without the engine's own words in brackets (a CFL number, a time step): what the
// presenter mode shows a class.
std::string failure_for_a_class(const std::string& what, double superficial_velocity,
                                double safe_velocity);

class ViewEngine {
 public:
  struct Options {
    double publish_interval = 0.005;  // wall s: the newest state is published at least this often
    bool start_running = true;
    double settle = ViewSession::kSettle;    // s, the live curve's settling time
    double average = ViewSession::kAverage;  // s, its averaging window
    UmfEstimate umf;           // the scene's measured U_mf (umf 0: not measured)
    std::string umf_shipped;   // the folder of shipped U_mf answers
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
  void started_again();
  void publish();
  void measure_speed(bool stopping);
  void stopped();  // the engine just stopped stepping: publish the state and its hash

  ViewSession session_;
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
  std::string error_, error_plain_, refusal_;
  std::chrono::steady_clock::time_point last_publish_{}, speed_t0_{};
  std::int64_t speed_steps0_ = 0;
  // Stepping spans shorter than the speed's quarter second (a script's `at T` lines) are summed
  // until they make one.
  double speed_span_s_ = 0.0;
  std::int64_t speed_span_steps_ = 0;
  double sim_s_per_wall_s_ = 0.0, steps_per_s_ = 0.0;

  mutable std::mutex status_mutex_;
  mutable std::condition_variable status_changed_;
  EngineStatus status_;
  std::vector<PlotSample> samples_;  // under status_mutex_
};

}  // namespace fluidbed::app
