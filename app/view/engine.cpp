#include "view/engine.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/errors.hpp"
#include "core/steps.hpp"
#include "dem/contact_law.hpp"
#include "run/bubble_recorder.hpp"
#include "run/packed_bed.hpp"
#include "sim/checks.hpp"

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

Settings with_contact(const Settings& scene, bool ideal, double stiffness) {
  Settings s = scene;
  if (stiffness > 0.0 && stiffness != scene.contact.stiffness) {
    if (!std::isfinite(stiffness)) throw InputError("the stiffness must be a finite number of N/m");
    s.contact.damping =
        damping_for_stiffness(scene.contact.damping, scene.contact.stiffness, stiffness);
    s.contact.stiffness = stiffness;
    const SceneCheck c = check_scene(s);
    if (!c.refusals.empty()) {
      char k[64];
      std::snprintf(k, sizeof k, "%g N/m", stiffness);
      throw InputError(std::string("stiffness ") + k +
                       " is refused for this scene: " + c.refusals.front());
    }
  }
  if (ideal) {
    s.contact.damping = 0.0;
    s.contact.friction = 0.0;
  }
  return s;
}

std::string failure_in_the_viewer(const std::string& what, double u) {
  std::string w = what;
  // The engine's advice for scene files; the viewer cannot change the time step.
  for (const char* advice : {": reduce the time step", "; reduce the time step"})
    if (const auto at = w.find(advice); at != std::string::npos)
      w.erase(at, std::string(advice).size());
  const char* meaning = "the bed could not be computed any further at this gas velocity";
  if (w.find("CFL") != std::string::npos)
    meaning = "the gas moved further in one time step than the scene's step allows";
  else if (w.find("overlap") != std::string::npos || w.find("porosity") != std::string::npos)
    meaning = "the gas pressed the particles into each other harder than the contacts can take";
  else if (w.find("left the bed") != std::string::npos)
    meaning = "the gas blew particles out of the bed";
  char speed[64];
  std::snprintf(speed, sizeof speed, "%.2f m/s", u);
  return std::string("The simulation stopped at U = ") + speed + ": " + meaning + " (" + w +
         "). Press Reset to start again from the packed bed, and keep the gas below " + speed + ".";
}

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
  Settings s = with_contact(scene_, ideal_, stiffness_);
  // The particles of the starting state (initial heights for the mixing colours come from it);
  // the caller then loads the whole state, gas and contact history included.
  s.particles.placement = Placement::State;
  s.particles.state_file = start_file_;
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
  if (on != ideal_) rebuild_keeping_state(on, stiffness_);
}

void ViewModel::set_stiffness(double k) {
  if (k == scene_.contact.stiffness) k = 0.0;
  if (k != stiffness_) rebuild_keeping_state(ideal_, k);
}

double ViewModel::stiffness() const {
  return stiffness_ > 0.0 ? stiffness_ : scene_.contact.stiffness;
}

void ViewModel::rebuild_keeping_state(bool ideal, double stiffness) {
  const bool old_ideal = ideal_;
  const double old_stiffness = stiffness_;
  ideal_ = ideal;
  stiffness_ = stiffness;
  try {
    auto next = build();  // refuses a stiffness the step cannot take before anything changes
    const std::string now = dir_ + "/switch.state";
    sim_->save_state(now);
    next->load_state(now);
    sim_ = std::move(next);
  } catch (...) {
    ideal_ = old_ideal;
    stiffness_ = old_stiffness;
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
    : model_(scene),
      options_(options),
      running_(options.start_running),
      curve_(options.settle, options.average, check_scene(scene).figures.weight_per_area,
             model_.sim().time(),
             model_.sim().gas() ? model_.sim().gas()->superficial_velocity() : 0.0),
      regime_(scene, model_.sim()) {
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
    case K::reset:  // the run/pause switch stays as it is, after a failure too
      model_.reset();
      regime_.restart(model_.sim());  // tracking starts again with the bed
      curve_.clear(model_.sim().time(), held_velocity());
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
      curve_.velocity(sim.time(), held_velocity());
      break;
    case K::ideal:
      model_.set_ideal(c.value != 0.0);
      curve_.restart_hold(model_.sim().time());
      break;
    case K::stiffness:
      model_.set_stiffness(c.value);
      curve_.restart_hold(model_.sim().time());
      break;
    case K::bubbles:
      bubbles_on_ = c.value != 0.0;
      break;
    case K::settle:
      curve_.set_times(sim.time(), c.value, curve_.state().window);
      break;
    case K::average:
      curve_.set_times(sim.time(), curve_.state().settle, c.value);
      break;
  }
}

double ViewEngine::held_velocity() const {
  const GasSolver* g = model_.sim().gas();
  return g ? g->superficial_velocity() : 0.0;
}

void ViewEngine::add_bubbles(Snapshot& snap) const {
  const std::shared_ptr<const BubbleView> v = regime_.view();
  if (!bubbles_on_ || !v) {  // snapshots come back from the pool with their old fields
    snap.void_fraction.clear();
    snap.bubble_edges.clear();
    return;
  }
  snap.void_nx = v->grid.nx;
  snap.void_ny = v->grid.ny;
  snap.void_dx = v->grid.dx;
  snap.void_dy = v->grid.dy;
  snap.void_fraction = v->void_fraction;
  snap.bubble_edges = v->edges;
}

void ViewEngine::publish() {
  const Simulation& sim = model_.sim();
  std::shared_ptr<Snapshot> snap = channel_.acquire();
  take_snapshot(sim, *snap);
  add_bubbles(*snap);
  // Filled before publishing, read only afterwards: the status and the snapshot agree.
  const double inlet = model_.inlet_jet_velocity();
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
    status_.ideal = model_.ideal();
    status_.stiffness = model_.stiffness();
    status_.run_until = until_step_ > sim.steps()
                            ? static_cast<double>(until_step_) * sim.settings().time.dt
                            : -1.0;
    status_.generation = generation_;
    status_.commands_applied = applied_;
    status_.error = error_;
    status_.refusal = refusal_;
    status_.curve = curve_.state();  // a few dozen points at most
    status_.bubbles = regime_.view();
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
  regime_.after_step(sim);
  interval_overlap_ = std::max(interval_overlap_, sim.dem().diagnostics().max_overlap_ratio);
  if (sim.time() + 0.5 * sim.settings().time.dt < next_sample_) return;
  next_sample_ += sample_interval_;
  if (sim.has_gas()) curve_.sample(sim.time(), sim.pressure_drop());
  const PlotSample s{sim.time(), sim.pressure_drop(), interval_overlap_};
  interval_overlap_ = 0.0;
  std::lock_guard lock(status_mutex_);
  // A viewer that stops draining (closing) must not make the engine grow without bound.
  if (samples_.size() < 200000) samples_.push_back(s);
}

void ViewEngine::measure_speed(bool stopping) {
  using Clock = std::chrono::steady_clock;
  const auto now = Clock::now();
  const double span = std::chrono::duration<double>(now - speed_t0_).count();
  if (!stopping && span < 0.25) return;
  const Simulation& sim = model_.sim();
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
        !error_.empty() || (!running_ && steps_left_ == 0 && until_step_ <= model_.sim().steps());
    const auto commands =
        queue_.take(idle ? std::chrono::milliseconds(50) : std::chrono::milliseconds(0));
    bool changed = false;
    for (const ViewCommand& c : commands) {
      try {
        apply(c);
      } catch (const InputError& e) {  // a refused value: said, and the bed goes on as it was
        refusal_ = e.what();
      } catch (const std::exception& e) {  // a rebuild that failed
        error_ = e.what();
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
    try {
      sim.step();
    } catch (const SimulationFailure& e) {
      // Stepping stops until Reset; the run/pause switch is left as the user set it.
      error_ = failure_in_the_viewer(e.what(), held_velocity());
      steps_left_ = 0;
      until_step_ = -1;
      continue;  // stopped() publishes the failed state and the message
    }
    sample_after_step();
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
