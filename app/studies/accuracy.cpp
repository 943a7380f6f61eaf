// Studies 1 (integrators and time step) and 2 (contact displacement): the same three tests at
// every step, for each variant (integrator, contact form):
//   drop      - one sphere dropped at 1 m/s onto the floor with eta = 0: apex height after the
//               10th bounce over the drop height (1 is exact);
//   restitution - the same drop with eta = 0.15, first bounce, averaged over contact phases (drop
//               heights spread over one step's travel), against the damped oscillator's e;
//   packing   - a dense frictionless packing at rest, run undamped: the change of its mechanical
//               energy (kinetic + m g y + 1/2 kappa delta^2) per particle in units of m g D; a run
//               that fails, or gains more than kGrowthLimit, is unstable at that step. Its wall
//               time per simulated second is the cost.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "scene/scene_loader.hpp"
#include "studies/accuracy_points.hpp"

namespace fluidbed::app::study {
namespace {
using accuracy::Config;
using accuracy::kDropSpeed;
using accuracy::kGrowthLimit;
using accuracy::RestState;
using accuracy::StepResult;
using accuracy::Variant;

// Accuracy that a user would accept: the rules of the advice paragraph.
constexpr double kDropTolerance = 0.01;         // 1 % of the drop height after 10 bounces
constexpr double kRestitutionTolerance = 0.01;  // in e

Config make_config(Size size, std::vector<Variant> variants, bool by_contact) {
  Config c;
  c.variants = std::move(variants);
  c.by_contact = by_contact;
  if (size == Size::Full) {
    c.multipliers = {0.1, 0.2, 0.35, 0.5, 0.7, 1.0, 1.25, 1.5, 1.75,
                     2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0, 8.0, 13.5};
  } else {
    c.multipliers = {0.25, 0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 13.5};
    c.phases = 3;
    c.drop_phases = 2;
    c.rest_count = 150;
    c.rest_width = 0.04;
    c.rest_height = 0.2;
    c.rest_fill = 0.1;
    c.settle_time = 0.25;
    c.energy_time = 0.03;
  }
  return c;
}

// Largest step below which every step of the variant is stable (NaN when the smallest is not).
double largest_stable(const std::vector<StepResult>& rs) {
  double best = NAN;
  for (const auto& r : rs) {
    if (!r.stable()) break;
    best = r.mult;
  }
  return best;
}

const StepResult* at_mult(const std::vector<StepResult>& rs, double mult) {
  for (const auto& r : rs)
    if (std::fabs(r.mult - mult) < 1e-9) return &r;
  return nullptr;
}

// Where the variant first fails each test (the multiplier), for "where does each fail".
struct FailPoints {
  double drop = NAN, restitution = NAN, stability = NAN;
};
FailPoints fail_points(const std::vector<StepResult>& rs) {
  FailPoints f;
  for (const auto& r : rs) {
    if (std::isnan(f.drop) && (!r.drop_ok || r.drop_err > kDropTolerance)) f.drop = r.mult;
    if (std::isnan(f.restitution) && (!r.rest_ok || r.e_err > kRestitutionTolerance))
      f.restitution = r.mult;
    if (std::isnan(f.stability) && !r.stable()) f.stability = r.mult;
  }
  return f;
}

std::string mult_text(double m) { return std::isnan(m) ? "none in range" : fmt("%gx", m); }

// Everything the study measured, by variant and step.
struct Accuracy {
  explicit Accuracy(const Config& c) : config(c) {}
  const Config& config;
  double m = 0.0;               // kg, the paper's sphere
  double tc = 0.0, tc9 = 0.0;   // s: its contact duration with a wall, and t_c / 9
  RestState rest;               // the settled packing the energy tests start from
  std::vector<std::vector<StepResult>> res;  // [variant][multiplier]
  std::vector<double> limits;   // each variant's largest stable multiplier (NaN: none)
};

// The series of one variant on the study's charts: its name, line with markers, its shape.
chart::Series variant_series(const Config& c, std::size_t v) {
  chart::Series s;
  s.label = c.variants[v].short_label(c.by_contact);
  s.mark = chart::Mark::LinePoints;
  s.shape = static_cast<chart::Shape>(v % 4);
  return s;
}

Accuracy measure(const Options& o, const Config& c) {
  Accuracy a(c);
  a.m = paper_particle_mass();
  a.tc = contact_duration(50000.0, a.m);
  a.tc9 = a.tc / 9.0;
  if (o.log) o.log("settling the packing for the energy test (" + std::to_string(c.rest_count) +
                   " frictionless spheres, " + fmt("%g s", c.settle_time) + ")");
  a.rest = make_rest_state(o, c);

  const std::size_t nv = c.variants.size(), nm = c.multipliers.size();
  // Heaviest points (the smallest steps) first.
  std::vector<std::size_t> order(nv * nm);
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) {
    return c.multipliers[p % nm] < c.multipliers[q % nm];
  });
  const std::vector<StepResult> flat = RunPool(o.workers).map<StepResult>(
      nv * nm,
      [&](std::size_t k) {
        const Variant& v = c.variants[k / nm];
        StepResult r = stored_step(o, c, a.rest, v, c.multipliers[k % nm]);
        if (o.log) {
          o.log("  " + v.label() + fmt(" dt = %.3gx", r.mult) +
                (r.stable() ? fmt(": drop error %.3g", r.drop_err) +
                                  fmt(", restitution error %.3g", r.e_err) +
                                  fmt(", energy drift %.3g m g D", r.drift) +
                                  fmt(", cost %.3g s/s", r.cost)
                            : ": failed: " + r.error()));
        }
        return r;
      },
      order);
  a.res.resize(nv);
  for (std::size_t k = 0; k < flat.size(); ++k) a.res[k / nm].push_back(flat[k]);
  for (const auto& rs : a.res) a.limits.push_back(largest_stable(rs));
  return a;
}

Table table(const Accuracy& a) {
  const Config& c = a.config;
  const auto& res = a.res;
  const std::size_t nv = c.variants.size();
  Table t({"variant", "integrator", "displacement", "dt_s", "dt_over_tc9", "dt_over_tc",
           "drop_height_ratio_10", "drop_error", "restitution", "restitution_analytic",
           "restitution_error", "restitution_spread", "energy_growth_mgd", "energy_drift_mgd",
           "stable", "cost_cpu_s_per_sim_s", "cost_wall_s_per_sim_s", "particle_steps_per_s",
           "status", "failure_kind", "failure"});
  const double e_th = restitution_from_damping(50000.0, 0.15, a.m);
  for (std::size_t v = 0; v < nv; ++v)
    for (const auto& r : res[v]) {
      t.add({c.variants[v].label(), option_string(c.variants[v].integrator),
             option_string(c.variants[v].displacement),
             num(r.dt), num(r.mult), num(r.dt / a.tc), num(r.drop_ratio), num(r.drop_err),
             num(r.e_mean), num(e_th), num(r.e_err), num(r.e_spread), num(r.growth),
             num(r.drift), r.stable() ? "yes" : "no", num(r.cost), num(r.cost_wall), num(r.psteps),
             r.failed() ? "failed" : "ok", r.kind(), r.error()},
            r.failed());
    }
  return t;
}

// Four panels against the step: drop error, restitution error, energy change, cost.
std::string accuracy_chart(const Accuracy& a, const std::string& dir) {
  const Config& c = a.config;
  const auto& res = a.res;
  const std::size_t nv = c.variants.size();
  auto panel = [&](const std::string& title, const std::string& ylabel, auto value) {
    chart::Chart ch = log_log_chart(title, "time step / (t_c / 9)", ylabel);
    for (std::size_t v = 0; v < nv; ++v) {
      chart::Series s = variant_series(c, v);
      for (const auto& r : res[v]) {
        s.x.push_back(r.mult);
        s.y.push_back(r.stable() ? value(r) : NAN);
      }
      ch.series.push_back(s);
    }
    ch.vlines.push_back({1.0, "t_c / 9 (paper)", {120, 120, 120}, true, 1.0});
    return ch;
  };
  std::vector<chart::Chart> acc = {
      panel("Drop test, 10 elastic bounces (mean over phases)", "|height / drop height - 1|",
            [](const StepResult& r) { return r.drop_err; }),
      panel("Restitution at eta = 0.15 (mean over phases)", "|e - e_analytic|",
            [](const StepResult& r) { return r.e_err; }),
      panel("Packing at rest, undamped: energy change", "|dE| per particle (m g D)",
            [](const StepResult& r) { return std::fabs(r.drift); }),
      panel("Cost of the packing test", "CPU s per simulated s",
            [](const StepResult& r) { return r.cost; })};
  acc[1].hlines.push_back({kRestitutionTolerance, "0.01", {150, 150, 150}, true, 1.0});
  acc[0].hlines.push_back({kDropTolerance, "1 %", {150, 150, 150}, true, 1.0});
  return write_grid(dir, "accuracy.png", acc, 2, 800, 520,
                    "Accuracy and cost against the time step (t_c = " + fmt("%.3g s", a.tc) +
                        ", pi sqrt(m / kappa), sphere-wall)");
}

// The largest energy gain against the step, failed runs marked at the top.
std::string stability_chart(const Accuracy& a, const std::string& dir) {
  const Config& c = a.config;
  const auto& res = a.res;
  const std::size_t nv = c.variants.size();
  chart::Chart st = log_log_chart(
      "Stability: largest energy gain of a packing at rest (failed runs at the top; no gain: no "
      "point)",
      "time step / (t_c / 9)", "largest energy gain per particle (m g D)");
  const double cap = 10.0;
  st.y.max = 30.0;
  for (std::size_t v = 0; v < nv; ++v) {
    chart::Series s = variant_series(c, v), f;
    s.colour = chart::palette(v);
    f.label = "";
    f.mark = chart::Mark::Points;
    f.shape = s.shape;
    f.filled = false;
    f.colour = chart::palette(v);
    f.marker_size = 11.0;
    for (const auto& r : res[v]) {
      s.x.push_back(r.mult);
      s.y.push_back(r.stable() && r.growth > 0.0 ? r.growth : NAN);
      f.x.push_back(r.mult);
      f.y.push_back(r.stable() ? NAN : cap * (1.0 + 0.25 * static_cast<double>(v)));
    }
    st.series.push_back(s);
    st.series.push_back(f);
  }
  // One marker line per distinct largest stable step, naming every variant that has it.
  std::map<double, std::vector<std::size_t>> by_limit;
  for (std::size_t v = 0; v < nv; ++v)
    if (const double ls = a.limits[v]; !std::isnan(ls)) by_limit[ls].push_back(v);
  for (const auto& [ls, vs] : by_limit) {
    std::string names;
    for (std::size_t v : vs)
      names += (names.empty() ? "" : ", ") + c.variants[v].short_label(c.by_contact);
    st.vlines.push_back({ls, "largest stable " + fmt("%gx: ", ls) + names,
                         vs.size() == 1 ? chart::palette(vs[0]) : chart::Rgb{60, 60, 60}, true,
                         2.0});
  }
  st.hlines.push_back({kGrowthLimit, "instability threshold", {150, 150, 150}, true, 1.0});
  return write_chart(dir, "stability.png", st);
}

// Drop-test error against cost, each point labelled with its step.
std::string speed_accuracy_chart(const Accuracy& a, const std::string& dir) {
  const Config& c = a.config;
  const auto& res = a.res;
  const std::size_t nv = c.variants.size();
  chart::Chart sa = log_log_chart(
      "Speed against accuracy: drop-test error against cost (labels: step / (t_c / 9))",
      "cost: CPU s per simulated s (packing of " + std::to_string(c.rest_count) + ")",
      "|height after 10 bounces / drop height - 1|");
  for (std::size_t v = 0; v < nv; ++v) {
    chart::Series s = variant_series(c, v);
    for (const auto& r : res[v]) {
      if (!r.stable() || !(r.drop_err > 0.0)) continue;
      s.x.push_back(r.cost);
      s.y.push_back(r.drop_err);
      s.point_labels.push_back(fmt("%g", r.mult));
    }
    sa.series.push_back(s);
  }
  return write_chart(dir, "speed_accuracy.png", sa);
}

std::string findings(const Accuracy& a) {
  const Config& c = a.config;
  const auto& res = a.res;
  const std::size_t nv = c.variants.size();
  const double e_th = restitution_from_damping(50000.0, 0.15, a.m);
  std::ostringstream md;
  md << "Time steps are multiples of t_c / 9 = " << fmt("%.4g s", a.tc9) << ", with the contact "
     << "duration t_c = pi sqrt(m / kappa) = " << fmt("%.4g s", a.tc)
     << " of a sphere against a wall (m = " << fmt("%.4g kg", a.m)
     << ", kappa = 50,000 N/m; a pair of spheres lasts t_c / sqrt 2). The paper's step, 1.5e-5 s, "
     << "is " << fmt("%.2fx", 1.5e-5 / a.tc9) << ".\n\n";
  md << "- drop test: a sphere dropped at " << kDropSpeed
     << " m/s impact speed, eta = 0; error = |apex after the 10th bounce / drop height - 1|, "
        "mean over " << c.drop_phases << " contact phases (drop heights spread over one step's "
        "travel: a single drop's error depends on where in a step its contacts begin).\n";
  md << "- restitution: eta = 0.15, the first bounce, mean over " << c.phases
     << " contact phases; analytic e = " << fmt("%.4f", e_th) << ".\n";
  md << "- packing: " << c.rest_count << " frictionless spheres settled in a box "
     << c.rest_width << " m wide (kinetic energy left " << fmt("%.2g", a.rest.kinetic_per_particle)
     << " m g D per particle, solid fraction " << fmt("%.3f", a.rest.solid_fraction)
     << "), then " << c.energy_time
     << " s undamped; energy change per particle in m g D = " << fmt("%.3g J", a.m * 9.81 * 0.004)
     << "; unstable when the run fails or the energy gains more than " << kGrowthLimit
     << " m g D per particle. Cost: seconds per simulated second of this packing on one thread "
     << "(its CPU time, the energy sampling excluded: equal to wall seconds on an idle core, and "
     << "not inflated by other programs sharing the machine).\n\n";
  md << "| variant | largest stable step | = dt | = t_c x | drop error at 1x | restitution error "
        "at 1x | energy change at 1x (m g D) | cost at 1x (s/s) | drop error > 1 % from | "
        "restitution error > 0.01 from |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t v = 0; v < nv; ++v) {
    const double ls = a.limits[v];
    const StepResult* one = at_mult(res[v], 1.0);
    const FailPoints f = fail_points(res[v]);
    md << "| " << c.variants[v].label() << " | " << mult_text(ls) << " | "
       << (std::isnan(ls) ? "-" : fmt("%.3g s", ls * a.tc9)) << " | "
       << (std::isnan(ls) ? "-" : fmt("%.2f", ls / 9.0)) << " | "
       << (one && one->stable() ? fmt("%.2g", one->drop_err) : "failed") << " | "
       << (one && one->stable() ? fmt("%.2g", one->e_err) : "failed") << " | "
       << (one && one->stable() ? fmt("%.2g", one->drift) : "failed") << " | "
       << (one && one->stable() ? fmt("%.3g", one->cost) : "failed") << " | "
       << mult_text(f.drop) << " | " << mult_text(f.restitution) << " |\n";
  }
  md << "\nFirst unstable step of each: ";
  for (std::size_t v = 0; v < nv; ++v) {
    const FailPoints f = fail_points(res[v]);
    const StepResult* first = nullptr;
    for (const auto& r : res[v])
      if (std::fabs(r.mult - f.stability) < 1e-9) first = &r;
    md << (v ? "; " : "") << c.variants[v].label() << " at " << mult_text(f.stability)
       << (first ? " (" + first->error() + ")" : "");
  }
  md << ".\n";
  // Study 1's note on symplectic Euler against the predictor-corrector.
  if (!c.by_contact) {
    double pc = NAN, se = NAN;
    for (std::size_t v = 0; v < nv; ++v) {
      if (c.variants[v].integrator == Integrator::Newmark) pc = a.limits[v];
      if (c.variants[v].integrator == Integrator::SymplecticEuler) se = a.limits[v];
    }
    std::ostringstream note;
    note << "\nSymplectic Euler's largest stable step " << mult_text(se)
         << " against the predictor-corrector's " << mult_text(pc) << ": ";
    if (!std::isnan(se) && !std::isnan(pc) && se < pc) {
      note << "smaller, as expected of a first-order scheme whose damping force lags by a step.\n";
    } else {
      note << "Note: not smaller. For an undamped linear spring all three schemes are stable "
              "up to omega dt = 2 (a von Neumann analysis of each update: the amplification of "
              "the predictor-corrector as coded, velocity Verlet and symplectic Euler all reach "
              "modulus 1 at omega dt = 2), so in an undamped packing the limit is set by the "
              "packing's highest contact frequency, the same for all three; symplectic Euler "
              "differs in accuracy (first order), not in stability, which is what the data "
              "shows.\n";
    }
    md << note.str();
  }

  return md.str();
}

std::string advice(const Accuracy& a) {
  const Config& c = a.config;
  const auto& res = a.res;
  const std::size_t nv = c.variants.size();
  // Which variant. Errors at t_c / 9, each over its tolerance and added: the score. The paper's
  // (the first variant, the default) is kept unless another, at least as stable, scores less
  // than half of it: single-step errors move with the contact phase by tens of per cent, so a
  // smaller difference is not a reason to change a default.
  auto score = [&](std::size_t v) {
    const StepResult* one = at_mult(res[v], 1.0);
    return one && one->stable() ? one->drop_err / kDropTolerance + one->e_err / kRestitutionTolerance
                                : INFINITY;
  };
  std::size_t best = 0;
  for (std::size_t v = 1; v < nv; ++v)
    if (score(v) < 0.5 * score(best) && !(a.limits[v] < a.limits[best]))
      best = v;
  // Its recommended step: the largest at which it is stable with accepted errors, and at most
  // two thirds of its largest stable step (a margin for denser contacts than the test's).
  double accurate = NAN;
  for (const auto& r : res[best]) {
    if (!r.stable() || r.drop_err > kDropTolerance || r.e_err > kRestitutionTolerance) break;
    accurate = r.mult;
  }
  double rec = accurate;
  if (!std::isnan(a.limits[best])) {
    double margin = NAN;
    for (double mm : c.multipliers)
      if (mm <= a.limits[best] * 2.0 / 3.0 + 1e-12) margin = mm;
    if (!std::isnan(margin)) rec = std::isnan(rec) ? margin : std::min(rec, margin);
  }
  std::ostringstream adv;
  adv << "Choose **" << c.variants[best].label() << "**. Rule: at t_c / 9 each variant's "
      << "drop-test error over 1 % plus its restitution error over 0.01 is its score; the paper's "
      << c.variants[0].label() << " is kept unless another, at least as stable, scores under half "
      << "of it. Scores:";
  for (std::size_t v = 0; v < nv; ++v)
    adv << (v ? ";" : "") << " " << c.variants[v].short_label(c.by_contact) << " "
        << fmt("%.2g", score(v));
  adv << ". ";
  if (!std::isnan(rec))
    adv << "With it, use a step of at most " << fmt("%gx", rec) << " t_c / 9 = "
        << fmt("%.3g s", rec * a.tc9)
        << " (rule: the largest step whose drop error stays below 1 % and restitution error "
           "below 0.01, and no more than 2/3 of the largest stable step, "
        << mult_text(a.limits[best]) << "). ";
  adv << "The paper's 1.5e-5 s (" << fmt("%.2fx", 1.5e-5 / a.tc9) << ") "
      << (!std::isnan(rec) && 1.5e-5 / a.tc9 <= rec + 0.02 ? "is inside that range"
                                                           : "is outside that range")
      << "; a smaller step buys accuracy at a cost that grows as 1/dt (the speed-accuracy chart).";
  return adv.str();
}

std::vector<std::string> charts(const Accuracy& a, const std::string& dir) {
  return {accuracy_chart(a, dir), stability_chart(a, dir), speed_accuracy_chart(a, dir)};
}

Report accuracy_study(const Options& o, const Config& c) {
  const auto measure_c = [&c](const Options& opt) { return measure(opt, c); };
  return run_steps<Accuracy>(o, {measure_c, table, charts, findings, advice});
}

}  // namespace

Report integrators_study(const Options& o) {
  const Config c = make_config(o.size,
                               {{Integrator::Newmark, Displacement::Incremental},
                                {Integrator::VelocityVerlet, Displacement::Incremental},
                                {Integrator::SymplecticEuler, Displacement::Incremental}},
                               false);
  return accuracy_study(o, c);
}

Report contact_study(const Options& o) {
  const Config c =
      make_config(o.size,
                  {{Integrator::Newmark, Displacement::Incremental},
                   {Integrator::Newmark, Displacement::Geometric}},
                  true);
  Report r = accuracy_study(o, c);
  r.findings +=
      "\nThe incremental form starts each contact's spring at the overlap it would have had at "
      "the moment of touching (eq 13), so a contact first seen late stores no fictitious energy; "
      "the geometric form takes the whole overlap at once. The restitution column shows the "
      "difference at large steps, where a contact begins mid-step; the energy column shows what "
      "each does to a packing whose contacts persist. Caveat: these tests are a sphere on a wall "
      "and a packing at rest; the case eqs 13-17 were made for, two particles closing fast and "
      "first seen deep in overlap, is not among them, so the advice below holds for these tests "
      "and says nothing about fast pair impacts.\n";
  return r;
}

}  // namespace fluidbed::app::study
