#include "view/engine.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/errors.hpp"
#include "core/steps.hpp"
#include "run/bubble_recorder.hpp"
#include "run/packed_bed.hpp"

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
// ViewModel

namespace {

// A folder only this process uses, under $TMPDIR (or /tmp).
std::string private_temp_dir() {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base && *base ? base : "/tmp") + "/fluidbed-view-XXXXXX";
  if (!mkdtemp(pattern.data()))
    throw InputError("cannot create a temporary folder under " +
                     pattern.substr(0, pattern.rfind('/')) + " for the viewer's starting state");
  return pattern;
}

}  // namespace

ViewModel::ViewModel(const Settings& scene) : scene_(scene), dir_(private_temp_dir()) {
  try {
    start_file_ = dir_ + "/start.state";
    Settings start = scene_;  // the scene as `run` starts it (packed bed from the cache)
    prepare_packed_bed(start);
    Simulation first(start);
    first.save_state(start_file_);
    // Every simulation of the viewer, the first included, is built the same way (solvers from
    // the settings, then the saved state), so a run after a reset is the run from the start.
    sim_ = build();
    sim_->load_state(start_file_);
    start_hash_ = sim_->state_hash();
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
    throw;
  }
}

ViewModel::~ViewModel() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

std::unique_ptr<Simulation> ViewModel::build() const {
  Settings s = scene_;
  // The particles of the starting state (initial heights for the mixing colours come from it);
  // the caller then loads the whole state, gas and contact history included.
  s.particles.placement = Placement::State;
  s.particles.state_file = start_file_;
  if (ideal_) {
    s.contact.damping = 0.0;
    s.contact.friction = 0.0;
  }
  return std::make_unique<Simulation>(s);
}

void ViewModel::reset() {
  auto fresh = build();
  fresh->load_state(start_file_);
  sim_ = std::move(fresh);
}

void ViewModel::set_velocity(double u) {
  sim_->set_superficial_velocity(std::max(0.0, u));
}

void ViewModel::set_ideal(bool on) {
  if (on == ideal_) return;
  const std::string now = dir_ + "/switch.state";
  sim_->save_state(now);
  ideal_ = on;
  try {
    auto next = build();
    next->load_state(now);
    sim_ = std::move(next);
  } catch (...) {
    ideal_ = !on;
    throw;
  }
}

double ViewModel::inlet_jet_velocity() const {
  const GasSolver* g = sim_->gas();
  if (!g) return 0.0;
  const auto& v = g->v();
  const auto nx = static_cast<std::size_t>(g->grid().nx);
  return v.empty() ? 0.0
                   : *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(nx));
}

// ---------------------------------------------------------------------------------------------
// ViewEngine

ViewEngine::ViewEngine(const Settings& scene, Options options)
    : model_(scene), options_(options), running_(options.start_running) {
  sample_interval_ =
      scene.diagnostics.output_interval > 0.0 ? scene.diagnostics.output_interval : 1e-3;
  next_sample_ = model_.sim().time() + sample_interval_;
  status_.start_hash = model_.start_hash();
  status_.state_hash = model_.start_hash();
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

void ViewEngine::apply(const ViewCommand& c) {
  using K = ViewCommand::Kind;
  Simulation& sim = model_.sim();
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
      const std::int64_t target = steps_for(c.value, sim.settings().time.dt);
      until_step_ = std::max(until_step_, target);
      break;
    }
    case K::reset:
      model_.reset();
      bubbles_.reset();  // tracking starts again with the bed
      bubbles_time_ = -1.0;
      ++generation_;
      steps_left_ = 0;
      until_step_ = -1;
      error_.clear();
      next_sample_ = model_.sim().time() + sample_interval_;
      interval_overlap_ = 0.0;
      {
        std::lock_guard lock(status_mutex_);
        samples_.clear();
      }
      break;
    case K::velocity:
      model_.set_velocity(c.value);
      break;
    case K::ideal:
      model_.set_ideal(c.value != 0.0);
      break;
    case K::bubbles:
      bubbles_on_ = c.value != 0.0;
      break;
  }
}

void ViewEngine::add_bubbles(const Simulation& sim, Snapshot& snap) {
  if (!bubbles_on_) {  // snapshots come back from the pool with their old fields
    snap.void_fraction.clear();
    snap.bubble_edges.clear();
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (!bubbles_ || (sim.time() != bubbles_time_ &&
                    now - bubbles_at_ >= std::chrono::duration<double>(kBubbleEvery))) {
    if (!bubbles_)
      bubbles_ = std::make_unique<BubbleAnalysis>(bubble_settings_for(sim.settings()),
                                                  bubble_geometry_for(sim.settings()));
    add_bubble_fields(*bubbles_, sim, bubble_fields_);
    bubbles_time_ = sim.time();
    bubbles_at_ = now;
  }
  snap.void_nx = bubble_fields_.void_nx;
  snap.void_ny = bubble_fields_.void_ny;
  snap.void_dx = bubble_fields_.void_dx;
  snap.void_dy = bubble_fields_.void_dy;
  snap.void_fraction = bubble_fields_.void_fraction;
  snap.bubble_edges = bubble_fields_.bubble_edges;
}

void ViewEngine::publish() {
  const Simulation& sim = model_.sim();
  std::shared_ptr<Snapshot> snap = channel_.acquire();
  take_snapshot(sim, *snap);
  add_bubbles(sim, *snap);
  // Filled before publishing, read only afterwards: the status and the snapshot agree.
  const double inlet = model_.inlet_jet_velocity();
  channel_.publish(std::move(snap));
  last_publish_ = std::chrono::steady_clock::now();
  {
    std::lock_guard lock(status_mutex_);
    status_.stepping = running_ || steps_left_ > 0 || until_step_ > sim.steps();
    status_.running = running_;
    status_.time = sim.time();
    status_.steps = sim.steps();
    status_.sim_s_per_wall_s = sim_s_per_wall_s_;
    status_.steps_per_s = steps_per_s_;
    status_.particles = sim.particle_count();
    status_.superficial_velocity = sim.gas() ? sim.gas()->superficial_velocity() : 0.0;
    status_.jet_velocity = sim.gas() ? sim.gas()->jet_velocity() : 0.0;
    status_.inlet_jet_velocity = inlet;
    status_.ideal = model_.ideal();
    status_.generation = generation_;
    status_.commands_applied = applied_;
    status_.error = error_;
  }
  status_changed_.notify_all();
}

void ViewEngine::stopped() {
  const std::uint64_t hash = model_.sim().state_hash();
  // The speed stays what it was while running: the panel shows it paused too.
  {
    std::lock_guard lock(status_mutex_);
    status_.state_hash = hash;
  }
  publish();
}

void ViewEngine::sample_after_step() {
  const Simulation& sim = model_.sim();
  interval_overlap_ = std::max(interval_overlap_, sim.dem().diagnostics().max_overlap_ratio);
  if (sim.time() + 0.5 * sim.settings().time.dt < next_sample_) return;
  next_sample_ += sample_interval_;
  const PlotSample s{sim.time(), sim.pressure_drop(), interval_overlap_};
  interval_overlap_ = 0.0;
  std::lock_guard lock(status_mutex_);
  // A viewer that stops draining (closing) must not make the engine grow without bound.
  if (samples_.size() < 200000) samples_.push_back(s);
}

void ViewEngine::loop() {
  using Clock = std::chrono::steady_clock;
  const auto publish_every = std::chrono::duration<double>(options_.publish_interval);
  bool was_stepping = true;
  speed_t0_ = Clock::now();
  speed_steps0_ = model_.sim().steps();
  while (!quit_.load()) {
    const bool idle = !running_ && steps_left_ == 0 && until_step_ <= model_.sim().steps();
    const auto commands =
        queue_.take(idle ? std::chrono::milliseconds(50) : std::chrono::milliseconds(0));
    bool changed = false;
    for (const ViewCommand& c : commands) {
      try {
        apply(c);
      } catch (const std::exception& e) {  // a refused value or a rebuild that failed
        error_ = e.what();
        running_ = false;
        steps_left_ = 0;
        until_step_ = -1;
      }
      ++applied_;
      changed = true;
    }
    if (quit_.load()) break;
    Simulation& sim = model_.sim();
    const bool stepping =
        error_.empty() && (running_ || steps_left_ > 0 || until_step_ > sim.steps());
    if (!stepping) {
      if (was_stepping || changed) stopped();
      was_stepping = false;
      continue;
    }
    if (!was_stepping) {
      speed_t0_ = Clock::now();
      speed_steps0_ = sim.steps();
    }
    was_stepping = true;
    try {
      sim.step();
    } catch (const SimulationFailure& e) {
      error_ = std::string("the simulation failed: ") + e.what();
      running_ = false;
      steps_left_ = 0;
      until_step_ = -1;
      continue;  // stopped() publishes the failed state and the message
    }
    sample_after_step();
    if (steps_left_ > 0) --steps_left_;
    if (until_step_ >= 0 && sim.steps() >= until_step_) until_step_ = -1;
    if (!running_ && steps_left_ == 0 && until_step_ < 0) {
      // Just stopped: the state's hash goes out with the status that says so, never after it.
      stopped();
      was_stepping = false;
      continue;
    }
    const auto now = Clock::now();
    const double span = std::chrono::duration<double>(now - speed_t0_).count();
    if (span >= 0.25) {
      const auto n = static_cast<double>(sim.steps() - speed_steps0_);
      steps_per_s_ = n / span;
      sim_s_per_wall_s_ = n * sim.settings().time.dt / span;
      speed_t0_ = now;
      speed_steps0_ = sim.steps();
    }
    if (changed || now - last_publish_ >= publish_every) publish();
  }
}

}  // namespace fluidbed::app
