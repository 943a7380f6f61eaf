#include "view/session.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/errors.hpp"
#include "dem/contact_law.hpp"
#include "run/packed_bed.hpp"
#include "sim/checks.hpp"

namespace fluidbed::app {

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
    if (scene.contact.law == ContactLaw::HertzMindlin)
      throw InputError("the stiffness is the linear law's; this scene's contacts are "
                       "Hertz-Mindlin (contact.youngs_modulus sets their stiffness)");
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
    if (s.contact.law == ContactLaw::HertzMindlin) s.contact.restitution = 1.0;
  }
  return s;
}

ViewModel::ViewModel(const Settings& scene)
    : opened_(scene), scene_(scene), dir_(private_temp_dir()) {
  try {
    start_file_ = dir_ + "/start.state";
    save_start(scene_);
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

void ViewModel::save_start(const Settings& scene) {
  Settings start = scene;  // the scene as `run` starts it (packed bed from the cache)
  prepare_packed_bed(start);
  Simulation first(start);
  first.save_state(start_file_);
}

Settings with_particles(const Settings& scene, double d, double rho) {
  const ParticleSettings& p0 = scene.particles;
  if (!(d > 0.0) || !std::isfinite(d))
    throw InputError("the particle diameter must be a positive number of metres");
  if (!(rho > 0.0) || !std::isfinite(rho))
    throw InputError("the particle density must be a positive number of kg/m^3");
  Settings s = scene;
  const double size = d / p0.diameter;
  const double mass = rho / p0.density * size * size * size;
  s.particles.diameter = d;
  s.particles.density = rho;
  if (scene.contact.law == ContactLaw::HertzMindlin) {
    s.time.dt = scene.time.dt * std::pow(mass, 0.4) * std::pow(size, -0.2);
  } else {
    s.time.dt = scene.time.dt * std::sqrt(mass);
    s.contact.damping = scene.contact.damping * std::sqrt(mass);
  }
  // The gas step is the gas's (its CFL, the coupling), measured for the scene: kept at most the
  // scene's, with as many particle steps in it as fit.
  const int steps = std::max(1, scene.coupling.particle_steps_per_gas_step);
  const double gas_step = scene.time.dt * steps;
  s.time.dt = std::min(s.time.dt, gas_step);
  s.coupling.particle_steps_per_gas_step =
      std::max(1, static_cast<int>(std::floor(gas_step / s.time.dt * (1.0 + 1e-12))));
  if (scene.domain.thickness <= p0.diameter * (1.0 + 1e-9)) s.domain.thickness = d;
  s.particles.fill_height = scene.particles.fill_height * size * size;
  s.particles.packing_scene.clear();
  s.packed_state.clear();
  char what[96];
  std::snprintf(what, sizeof what, "spheres of %.3g mm and %.4g kg/m^3", 1000.0 * d, rho);
  if (d > s.domain.thickness * (1.0 + 1e-9))
    throw InputError(std::string(what) + " do not fit between the front and back walls (" +
                     std::to_string(1000.0 * s.domain.thickness) + " mm apart)");
  const SceneCheck c = check_scene(s);
  if (!c.refusals.empty())
    throw InputError(std::string(what) + " are refused for this scene: " + c.refusals.front());
  return s;
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

void ViewModel::set_particles(double diameter, double density,
                              const std::function<void(const std::string&)>& notify) {
  const ParticleSettings& p = opened_.particles;
  const bool own = (diameter == 0.0 && density == 0.0) ||
                   (diameter == p.diameter && density == p.density);
  const Settings next = own ? opened_ : with_particles(opened_, diameter, density);
  with_contact(next, ideal_, stiffness_);  // a stiffness the new step cannot take: refused here
  const std::string saved = dir_ + "/next-start.state";
  try {
    Settings start = next;
    prepare_packed_bed(start, notify);
    Simulation first(start);
    first.save_state(saved);  // nothing has changed until it is written over the old start
  } catch (const InputError& e) {  // the domain cannot hold them, ...: said with what was asked
    char what[96];
    std::snprintf(what, sizeof what, "spheres of %.3g mm and %.4g kg/m^3: ",
                  1000.0 * next.particles.diameter, next.particles.density);
    throw InputError(what + std::string(e.what()));
  }
  std::filesystem::rename(saved, start_file_);
  scene_ = next;
  sim_ = build();
  sim_->load_state(start_file_);
  start_hash_ = sim_->state_hash();
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
// ViewSession

ViewSession::ViewSession(const Settings& scene, double settle, double average)
    : model_(scene),
      curve_(settle, average, check_scene(scene).figures.weight_per_area, model_.sim().time(),
             held_velocity()),
      regime_(scene, model_.sim()) {
  sample_interval_ =
      scene.diagnostics.output_interval > 0.0 ? scene.diagnostics.output_interval : 1e-3;
  next_sample_ = model_.sim().time() + sample_interval_;
}

void ViewSession::set_umf(const UmfEstimate& scene_umf, const std::string& shipped) {
  scene_umf_ = umf_ = scene_umf;
  umf_shipped_ = shipped;
}

void ViewSession::start_again() {
  failed_velocity_ = -1.0;
  steps_at_velocity_ = 0;
  at_top_since_ = -1.0;
  held_at_top_ = 0;
  next_sample_ = model_.sim().time() + sample_interval_;
  interval_overlap_ = 0.0;
}

double ViewSession::held_velocity() const {
  const GasSolver* g = model_.sim().gas();
  return g ? g->superficial_velocity() : 0.0;
}

void ViewSession::apply(const ViewCommand& c,
                        const std::function<void(const std::string&)>& notify) {
  using K = ViewCommand::Kind;
  const Simulation& sim = model_.sim();
  switch (c.kind) {
    case K::run:
    case K::pause:
    case K::step:
    case K::run_until:
      break;
    case K::reset: {
      // The teacher's velocity stays; the one the bed just failed at gives way to the last one
      // it ran at.
      double u = held_velocity();
      if (failed_velocity_ >= 0.0 && u == failed_velocity_ && safe_velocity_ >= 0.0)
        u = safe_velocity_;
      model_.reset();
      if (model_.sim().gas() && u != held_velocity()) model_.set_velocity(u);
      start_again();
      regime_.restart(model_.sim());  // tracking starts again with the bed
      curve_.clear(model_.sim().time(), held_velocity());
      break;
    }
    case K::particles: {
      const double u = held_velocity();
      const double old_d = model_.scene().particles.diameter;
      const double old_rho = model_.scene().particles.density;
      model_.set_particles(c.value, c.density, notify);
      if (model_.sim().gas() && u != held_velocity()) model_.set_velocity(u);
      start_again();
      safe_velocity_ = -1.0;  // of other particles
      const Settings& now = model_.scene();
      regime_ = RegimeWatch(now, model_.sim());
      curve_.clear(model_.sim().time(), held_velocity(), check_scene(now).figures.weight_per_area);
      if (now.particles.diameter != old_d || now.particles.density != old_rho) {
        const Settings& opened = model_.opened_scene();
        const bool scenes_own = now.particles.diameter == opened.particles.diameter &&
                                now.particles.density == opened.particles.density;
        if (!(scene_umf_.umf > 0.0) || !now.gas.enabled || scenes_own)
          umf_ = scene_umf_;
        else
          try {
            umf_ = umf_for_particles(scene_umf_, opened, now, notify, umf_shipped_);
          } catch (const std::exception& e) {  // the bed runs; the presets wait for a U_mf
            if (notify) notify(std::string("no U_mf for the new particles: ") + e.what());
            umf_ = UmfEstimate{};
          }
        ++particles_changes_;
      }
      break;
    }
    case K::velocity:
      if (std::max(0.0, c.value) != held_velocity()) {
        // The velocity left behind ran long enough without failing: the safe one.
        if (steps_at_velocity_ >= kSafeSteps) safe_velocity_ = held_velocity();
        steps_at_velocity_ = 0;
      }
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

std::optional<PlotSample> ViewSession::step() {
  Simulation& sim = model_.sim();
  sim.step();
  ++steps_at_velocity_;
  regime_.after_step(sim);
  interval_overlap_ = std::max(interval_overlap_, sim.dem().diagnostics().max_overlap_ratio);
  if (sim.time() + 0.5 * sim.settings().time.dt < next_sample_) return std::nullopt;
  next_sample_ += sample_interval_;
  if (sim.has_gas()) curve_.sample(sim.time(), sim.pressure_drop());
  watch_the_top();
  const PlotSample s{sim.time(), sim.pressure_drop(), interval_overlap_};
  interval_overlap_ = 0.0;
  return s;
}

void ViewSession::watch_the_top() {
  const Simulation& sim = model_.sim();
  const Settings& s = sim.settings();
  held_at_top_ = 0;
  if (!s.domain.top_wall) return;
  const Particles& p = sim.dem().particles();
  int touching = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.y[i] + 1.05 * p.radius[i] >= s.domain.height) ++touching;
  if (touching == 0) {
    at_top_since_ = -1.0;
    return;
  }
  if (at_top_since_ < 0.0) at_top_since_ = sim.time();
  if (sim.time() - at_top_since_ >= kHeldAtTop - 1e-9) held_at_top_ = touching;
}

void ViewSession::snapshot(Snapshot& snap) const {
  take_snapshot(model_.sim(), snap);
  const std::shared_ptr<const BubbleView> v = regime_.view();
  if (!bubbles_on_ || !v) {
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

}  // namespace fluidbed::app
