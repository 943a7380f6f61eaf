#include "view/engine.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "core/steps.hpp"
#include "core/text_format.hpp"

namespace fluidbed::app {

// ---------------------------------------------------------------------------------------------
// CommandQueue

void CommandQueue::push(const ViewCommand& c) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(c);
  }
  changed_.notify_one();
}

std::vector<ViewCommand> CommandQueue::take(std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  if (queue_.empty() && wait.count() > 0)
    changed_.wait_for(lock, wait, [this] { return !queue_.empty() || woken_; });
  woken_ = false;
  std::vector<ViewCommand> out;
  out.swap(queue_);
  return out;
}

void CommandQueue::wake() {
  {
    std::lock_guard lock(mutex_);
    woken_ = true;
  }
  changed_.notify_one();
}

// ---------------------------------------------------------------------------------------------
// ViewEngine

namespace {

// A failure's meaning for the bed and what to do in the viewer.
std::pair<std::string, std::string> failure_words(const std::string& what, double u, double safe) {
  const char* meaning = "the bed could not be computed any further at this gas velocity";
  if (what.find("CFL") != std::string::npos)
    meaning = "the gas moved further in one time step than the scene's step allows";
  else if (what.find("overlap") != std::string::npos || what.find("porosity") != std::string::npos)
    meaning = "the gas pressed the particles into each other harder than the contacts can take";
  else if (what.find("left the bed") != std::string::npos)
    meaning = "the gas blew particles out of the bed";
  const std::string what_to_do =
      safe >= 0.0 && safe < u
          ? "Press Reset to start again from the packed bed at U = " +
                format_number("%.2f m/s", safe) + ", the last velocity it ran at"
          : "Lower the gas, then press Reset to start again from the packed bed at that velocity";
  return {meaning, what_to_do};
}

}  // namespace

std::string failure_in_the_viewer(const std::string& what, double u, double safe) {
  const auto [meaning, what_to_do] = failure_words(what, u, safe);
  const std::string speed = format_number("%.2f m/s", u);
  return std::string("The simulation stopped at U = ") + speed + ": " + meaning + " (" + what +
         "). " + what_to_do + "; keep the gas below " + speed + ".";
}

std::string failure_for_a_class(const std::string& what, double u, double safe) {
  const auto [meaning, what_to_do] = failure_words(what, u, safe);
  return std::string("The simulation stopped at U = ") + format_number("%.2f m/s", u) + ": " +
         meaning + ". " + what_to_do + ".";
}

ViewEngine::ViewEngine(const Settings& scene, Options options)
    : session_(scene, options.settle, options.average),
      options_(options),
      running_(options.start_running) {
  session_.set_umf(options.umf, options.umf_shipped);
  status_.start_hash = session_.model().start_hash();
  status_.state_hash = session_.model().start_hash();
  publish();  // the starting state, before the thread runs
}

ViewEngine::~ViewEngine() {
  stop();
}

void ViewEngine::start() {
  if (thread_.joinable()) return;
  quit_.store(false);
  thread_ = std::thread([this] { loop(); });
}

void ViewEngine::stop() {
  quit_.store(true);
  queue_.wake();
  if (thread_.joinable()) thread_.join();
}

std::uint64_t ViewEngine::post(const ViewCommand& c) {
  const std::uint64_t n = posted_.fetch_add(1) + 1;
  queue_.push(c);
  return n;
}

EngineStatus ViewEngine::status() const {
  std::lock_guard lock(status_mutex_);
  return status_;
}

std::vector<PlotSample> ViewEngine::take_samples() {
  std::vector<PlotSample> out;
  std::lock_guard lock(status_mutex_);
  out.swap(samples_);
  return out;
}

bool ViewEngine::wait_until_stopped(std::chrono::milliseconds timeout) const {
  std::unique_lock lock(status_mutex_);
  return status_changed_.wait_for(lock, timeout, [this] {
    return status_.commands_applied >= posted_.load() && !status_.stepping;
  });
}

// A new start (reset, new particles): the plots start again, pending steps and a failure go.
void ViewEngine::started_again() {
  ++generation_;
  steps_left_ = 0;
  until_step_ = -1;
  error_.clear();
  error_plain_.clear();
  std::lock_guard lock(status_mutex_);
  samples_.clear();
}

// The stepping commands are the engine's; the rest change the session.
void ViewEngine::apply(const ViewCommand& c) {
  using K = ViewCommand::Kind;
  switch (c.kind) {
    case K::run:
      running_ = true;
      break;
    case K::pause:
      running_ = false;
      steps_left_ = 0;
      until_step_ = -1;
      break;
    case K::step:
      running_ = false;
      steps_left_ += std::max<std::int64_t>(1, std::llround(c.value));
      break;
    case K::run_until: {
      const std::int64_t target = steps_for(c.value, session_.sim().settings().time.dt);
      until_step_ = std::max(until_step_, target);
      break;
    }
    case K::reset:  // the run/pause switch stays as it is, after a failure too
      session_.apply(c);
      started_again();
      break;
    case K::particles: {
      // Seconds of work (a packing, the force balances): the panel says so meanwhile.
      auto say = [this](const std::string& line) {
        {
          std::lock_guard lock(status_mutex_);
          status_.busy = line;
        }
        status_changed_.notify_all();
      };
      say(c.value > 0.0 ? format_number("packing a bed of %.1f mm spheres", 1000.0 * c.value) +
                              format_number(" of %.0f kg/m^3", c.density)
                        : std::string("packing the scene's own bed"));
      try {
        session_.apply(c, say);
      } catch (...) {
        say("");
        throw;
      }
      say("");
      started_again();
      break;
    }
    default:
      session_.apply(c);
      break;
  }
}

void ViewEngine::publish() {
  const Simulation& sim = session_.sim();
  std::shared_ptr<Snapshot> snap = channel_.acquire();
  session_.snapshot(*snap);
  // Filled before publishing, read only afterwards: the status and the snapshot agree.
  const double inlet = session_.model().inlet_jet_velocity();
  channel_.publish(std::move(snap));
  last_publish_ = std::chrono::steady_clock::now();
  {
    std::lock_guard lock(status_mutex_);
    status_.stepping = error_.empty() && (running_ || steps_left_ > 0 || until_step_ > sim.steps());
    status_.running = running_;
    status_.time = sim.time();
    status_.steps = sim.steps();
    status_.sim_s_per_wall_s = sim_s_per_wall_s_;
    status_.steps_per_s = steps_per_s_;
    status_.particles = sim.particle_count();
    status_.superficial_velocity = sim.gas() ? sim.gas()->superficial_velocity() : 0.0;
    status_.jet_velocity = sim.gas() ? sim.gas()->jet_velocity() : 0.0;
    status_.inlet_jet_velocity = inlet;
    status_.ideal = session_.model().ideal();
    status_.stiffness = sim.settings().contact.law == ContactLaw::HertzMindlin
                            ? 0.0
                            : session_.model().stiffness();
    status_.run_until = until_step_ > sim.steps()
                            ? static_cast<double>(until_step_) * sim.settings().time.dt
                            : -1.0;
    status_.generation = generation_;
    status_.commands_applied = applied_;
    status_.error = error_;
    status_.error_plain = error_plain_;
    status_.refusal = refusal_;
    status_.curve = session_.curve();  // a few dozen points at most
    status_.held_at_top = session_.held_at_top();
    status_.bubbles = session_.bubbles();
    status_.particle_diameter = sim.settings().particles.diameter;
    status_.particle_density = sim.settings().particles.density;
    status_.dt = sim.settings().time.dt;
    const UmfEstimate& umf = session_.umf();
    if (status_.particles_changes != session_.particles_changes() || status_.umf_method.empty()) {
      status_.umf = umf.umf;
      status_.umf_cached = umf.from_cache;
      status_.umf_method = umf.umf > 0.0 ? umf.method() : "";
      status_.umf_method_short = umf.umf > 0.0 ? umf.method_short() : "";
      status_.particles_changes = session_.particles_changes();
    }
  }
  status_changed_.notify_all();
}

void ViewEngine::stopped() {
  const std::uint64_t hash = session_.sim().state_hash();
  // The speed stays what it was while running: the panel shows it paused too.
  {
    std::lock_guard lock(status_mutex_);
    status_.state_hash = hash;
  }
  publish();
}

void ViewEngine::measure_speed(bool stopping) {
  using Clock = std::chrono::steady_clock;
  const auto now = Clock::now();
  const double span = std::chrono::duration<double>(now - speed_t0_).count();
  if (!stopping && span < 0.25) return;
  const Simulation& sim = session_.sim();
  speed_span_s_ += span;
  speed_span_steps_ += sim.steps() - speed_steps0_;
  speed_t0_ = now;
  speed_steps0_ = sim.steps();
  // A quarter second of stepping, or, before any figure, the first runs once they make 20 ms.
  const bool first = sim_s_per_wall_s_ == 0.0 && speed_span_steps_ > 0 && speed_span_s_ >= 0.02;
  if (speed_span_s_ >= 0.25 || first) {
    steps_per_s_ = static_cast<double>(speed_span_steps_) / speed_span_s_;
    sim_s_per_wall_s_ = steps_per_s_ * sim.settings().time.dt;
    speed_span_s_ = 0.0;
    speed_span_steps_ = 0;
  }
}

void ViewEngine::loop() {
  using Clock = std::chrono::steady_clock;
  const auto publish_every = std::chrono::duration<double>(options_.publish_interval);
  bool was_stepping = false, first = true;
  while (!quit_.load()) {
    const bool idle =
        !error_.empty() || (!running_ && steps_left_ == 0 && until_step_ <= session_.sim().steps());
    const auto commands =
        queue_.take(idle ? std::chrono::milliseconds(50) : std::chrono::milliseconds(0));
    bool changed = false;
    for (const ViewCommand& c : commands) {
      try {
        apply(c);
      } catch (const InputError& e) {  // a refused value: said, and the bed goes on as it was
        refusal_ = e.what();
      } catch (const std::exception& e) {  // a rebuild that failed
        error_ = error_plain_ = e.what();
        steps_left_ = 0;
        until_step_ = -1;
      }
      ++applied_;
      changed = true;
    }
    if (quit_.load()) break;
    const Simulation& sim = session_.sim();
    const bool stepping =
        error_.empty() && (running_ || steps_left_ > 0 || until_step_ > sim.steps());
    if (!stepping) {
      if (was_stepping) measure_speed(true);
      if (was_stepping || changed || first) stopped();
      was_stepping = first = false;
      continue;
    }
    if (!was_stepping) {
      speed_t0_ = Clock::now();
      speed_steps0_ = sim.steps();
    }
    was_stepping = true;
    std::optional<PlotSample> sample;
    try {
      sample = session_.step();
    } catch (const SimulationFailure& e) {
      // Stepping stops until Reset; the run/pause switch is left as the user set it.
      session_.failed();
      error_ = failure_in_the_viewer(e.what(), session_.held_velocity(),
                                     session_.safe_velocity());
      error_plain_ =
          failure_for_a_class(e.what(), session_.held_velocity(), session_.safe_velocity());
      steps_left_ = 0;
      until_step_ = -1;
      continue;  // stopped() publishes the failed state and the message
    }
    if (sample) {
      std::lock_guard lock(status_mutex_);
      // A viewer that stops draining (closing) must not make the engine grow without bound.
      if (samples_.size() < 200000) samples_.push_back(*sample);
    }
    if (steps_left_ > 0) --steps_left_;
    if (until_step_ >= 0 && sim.steps() >= until_step_) until_step_ = -1;
    if (!running_ && steps_left_ == 0 && until_step_ < 0) {
      // Just stopped: the state's hash goes out with the status that says so, never after it.
      measure_speed(true);
      stopped();
      was_stepping = false;
      continue;
    }
    measure_speed(false);
    if (changed || Clock::now() - last_publish_ >= publish_every) publish();
  }
}

}  // namespace fluidbed::app
