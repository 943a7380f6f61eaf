// The points of studies 1 and 2: the drop and restitution tests (one sphere on the floor over
// contact phases), the packing test (a dense packing at rest run undamped), and the settled
// packing it starts from (see accuracy_points.hpp and accuracy.cpp).
#include "studies/accuracy_points.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "analysis/bounce_tracker.hpp"
#include "analysis/mechanical_energy.hpp"
#include "core/hash.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"
#include "scene/scene_loader.hpp"
#include "sim/simulation.hpp"

namespace fluidbed::app::study::accuracy {
namespace fs = std::filesystem;
namespace {

struct DropRun {
  bool ok = false;
  std::string error;
  std::vector<double> heights, restitutions;
  double drop_height = 0.0;
};

Settings drop_settings(const Variant& v, double dt, double damping, double gap) {
  Settings s = drop_scene(0.002 + gap);
  s.particles.x = 0.075;
  s.time.dt = dt;
  s.time.integrator = v.integrator;
  s.contact.displacement = v.displacement;
  s.contact.damping = damping;
  return s;
}

DropRun drop_run(const Variant& v, double dt, double damping, double gap, int bounces) {
  DropRun r;
  const Settings s = drop_settings(v, dt, damping, gap);
  const double g = s.physics.gravity;
  const double flight = 2.0 * std::sqrt(2.0 * gap / g);
  const double limit = 1.5 * (0.5 + bounces) * flight + 0.01;
  try {
    Simulation sim(s);
    BounceTracker tracker(sim.dem(), g);
    r.drop_height = tracker.drop_height();
    const auto steps = static_cast<std::int64_t>(limit / dt);
    for (std::int64_t k = 0; k < steps; ++k) {
      sim.step();
      tracker.observe(sim.dem());
      if (static_cast<int>(tracker.apex_heights().size()) >= bounces) break;
    }
    r.heights = tracker.apex_heights();
    r.restitutions = tracker.restitutions();
    if (static_cast<int>(r.heights.size()) < bounces) {
      std::ostringstream os;
      os << "the drop made " << r.heights.size() << " of " << bounces << " bounces in " << limit
         << " s (bounces of a growing height: energy is being gained)";
      r.error = os.str();
      return r;
    }
    r.ok = true;
  } catch (const SimulationFailure& e) {
    r.error = std::string("drop test: ") + e.what();
  }
  return r;
}

// What a stored step point keeps (stored_point).
template <class R, class F>
void step_fields(R& r, F&& f) {
  f("mult", r.mult);
  f("dt", r.dt);
  f("drop_ok", r.drop_ok);
  f("rest_ok", r.rest_ok);
  f("pack_ok", r.pack_ok);
  f("drop_error", r.drop_error);
  f("rest_error", r.rest_error);
  f("pack_error", r.pack_error);
  f("pack_kind", r.pack_kind);
  f("drop_ratio", r.drop_ratio);
  f("drop_err", r.drop_err);
  f("e_mean", r.e_mean);
  f("e_err", r.e_err);
  f("e_spread", r.e_spread);
  f("growth", r.growth);
  f("drift", r.drift);
  f("cost", r.cost);
  f("cost_wall", r.cost_wall);
  f("psteps", r.psteps);
}
const auto kStepFields = [](auto& r, auto&& f) { step_fields(r, f); };

}  // namespace

RestState make_rest_state(const Options& o, const Config& c) {
  const std::string& dir = o.out;
  Settings s;
  s.scene.name = "rest-packing";
  s.scene.kind = SceneKind::Bed;
  s.domain.width = c.rest_width;
  s.domain.height = c.rest_height;
  s.particles.count = c.rest_count;
  s.particles.placement = Placement::Lattice;
  s.particles.fill_height = c.rest_fill;
  s.contact.friction = 0.0;
  s.contact.damping = 0.5;
  s.time.dt = contact_duration(s.contact.stiffness, paper_particle_mass()) / 18.0;
  s.diagnostics.averaging_start = 0.0;
  Simulation sim(s);
  RunOptions opt;
  opt.until = c.settle_time;
  const RunResult r = run_to_end(o, sim, opt);
  RestState rs;
  rs.path = fs::absolute(fs::path(dir) / "rest.state").string();
  sim.save_state(rs.path);
  rs.settings = s;
  const double mgd = paper_particle_mass() * s.physics.gravity * s.particles.diameter;
  rs.kinetic_per_particle = r.summary.value("kinetic_energy_final_j", 0.0) / (mgd * c.rest_count);
  rs.solid_fraction = r.summary.value("solid_fraction", 0.0);
  rs.bed_height = r.summary.value("bed_height_m", 0.0);
  return rs;
}

namespace {

void packing_test(const Options& o, const Config& c, const RestState& rest, const Variant& v,
                  StepResult& out) {
  Settings s = rest.settings;
  s.particles.placement = Placement::State;
  s.particles.state_file = rest.path;
  s.contact.damping = 0.0;
  s.contact.friction = 0.0;
  s.time.dt = out.dt;
  s.time.integrator = v.integrator;
  s.contact.displacement = v.displacement;
  s.diagnostics.output_interval = c.energy_time / 20.0;
  const double g = s.physics.gravity;
  const double scale = paper_particle_mass() * g * s.particles.diameter * c.rest_count;
  const std::int64_t steps = steps_for(c.energy_time, out.dt);
  const std::int64_t every = std::max<std::int64_t>(1, steps / 200);
  double sample_time = 0.0, e0 = 0.0, growth = 0.0, last = 0.0;
  RunOptions opt;
  opt.on_step = [&](const Simulation& sim) {
    if (sim.steps() % every != 0 && sim.steps() != steps) return;
    const double t0 = thread_cpu_seconds();
    const double e =
        mechanical_energy(sim.dem().particles(), sim.dem().walls(), s.contact.stiffness, g).total();
    sample_time += thread_cpu_seconds() - t0;
    if (!std::isfinite(e)) throw SimulationFailure("mechanical energy is not finite (NaN)");
    last = (e - e0) / scale;
    growth = std::max(growth, last);
    if (growth > kGrowthLimit) {
      std::ostringstream os;
      os.precision(3);
      os << "energy grew by " << growth << " m g D per particle (limit " << kGrowthLimit
         << ") at t = " << sim.time() << " s: unstable at this step";
      throw SimulationFailure(os.str());
    }
  };
  PointRun p;
  double start = 0.0;
  auto wall_start = std::chrono::steady_clock::now();
  try {
    Simulation sim(s);
    e0 =
        mechanical_energy(sim.dem().particles(), sim.dem().walls(), s.contact.stiffness, g).total();
    opt.until = c.energy_time;
    start = thread_cpu_seconds();
    wall_start = std::chrono::steady_clock::now();
    p.result = run_to_end(o, sim, opt);
    p.ok = true;
  } catch (const SimulationFailure& e) {
    p.error = e.what();
    p.kind = failure_kind(p.error);
  }
  const double cpu = thread_cpu_seconds() - start - sample_time;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count() -
      sample_time;
  out.growth = growth;
  out.pack_ok = p.ok;
  out.pack_error = p.ok ? "" : "packing test: " + p.error;
  out.pack_kind = p.kind;
  if (p.ok) {
    out.drift = last;
    out.cost = cpu / c.energy_time;
    out.cost_wall = wall / c.energy_time;
    out.psteps = static_cast<double>(steps) * c.rest_count / cpu;
  }
}

StepResult measure_step(const Options& o, const Config& c, const RestState& rest, const Variant& v,
                        double mult) {
  StepResult r;
  const double m = paper_particle_mass();
  const double tc = contact_duration(50000.0, m);
  r.mult = mult;
  r.dt = mult * tc / 9.0;
  const double gap = kDropSpeed * kDropSpeed / (2.0 * 9.81);
  // Drop test, elastic, over contact phases (one drop height alone is a lottery of where in a
  // step each contact begins): the mean ratio and the mean of |ratio - 1|.
  r.drop_ok = true;
  double ratio_sum = 0.0, err_sum = 0.0;
  for (int k = 0; k < c.drop_phases && r.drop_ok; ++k) {
    const DropRun d = drop_run(v, r.dt, 0.0, gap + kDropSpeed * r.dt * k / c.drop_phases, 10);
    r.drop_ok = d.ok;
    r.drop_error = d.error;
    if (!d.ok) break;
    ratio_sum += d.heights[9] / d.drop_height;
    err_sum += std::fabs(d.heights[9] / d.drop_height - 1.0);
  }
  if (r.drop_ok) {
    r.drop_ratio = ratio_sum / c.drop_phases;
    r.drop_err = err_sum / c.drop_phases;
  }
  // Restitution at eta = 0.15 over contact phases.
  std::vector<double> es;
  for (int k = 0; k < c.phases && r.rest_error.empty(); ++k) {
    const DropRun e = drop_run(v, r.dt, 0.15, gap + kDropSpeed * r.dt * k / c.phases, 1);
    if (!e.ok || e.restitutions.empty()) {
      r.rest_error = e.error.empty() ? "no bounce" : e.error;
      break;
    }
    es.push_back(e.restitutions.front());
  }
  if (r.rest_error.empty()) {
    r.rest_ok = true;
    double sum = 0.0;
    for (double e : es) sum += e;
    r.e_mean = sum / static_cast<double>(es.size());
    r.e_err = std::fabs(r.e_mean - restitution_from_damping(50000.0, 0.15, m));
    const auto [lo, hi] = std::minmax_element(es.begin(), es.end());
    r.e_spread = *hi - *lo;
  }
  packing_test(o, c, rest, v, r);
  return r;
}

}  // namespace

StepResult stored_step(const Options& o, const Config& c, const RestState& rest, const Variant& v,
                       double mult) {
  const nlohmann::json what = {{"point", "accuracy_step"},
                               {"variant", v.label()},
                               {"mult", mult},
                               {"rest", to_toml(rest.settings)},
                               {"rest_state", file_digest(rest.path)}};
  return stored_fields<StepResult>(o, what, kStepFields,
                                   [&] { return measure_step(o, c, rest, v, mult); });
}

}  // namespace fluidbed::app::study::accuracy
