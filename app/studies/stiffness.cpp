// Study 3: the paper's stiff spring (kappa = 50,000 N/m) against Tsuji's soft one (800 N/m). Each
// at its own step, t_c / 9 with t_c = pi sqrt(m / kappa) (the paper's rule: 1.5e-5 s for the stiff
// spring): the packing (0.8 s falling in still air, as the paper's), then the jetted bed at
// 2.8 m/s from it. Max overlap, the bed's behaviour (dp, its fluctuation and period, the height
// the bed reaches) and the cost of each.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/errors.hpp"
#include "run/packed_bed.hpp"
#include "sim/simulation.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace {
namespace fs = std::filesystem;

struct StiffPoint {
  double k = 0.0, tc = 0.0, dt = 0.0;
  PointRun packing, bed;
  double rest_overlap = NAN;  // max overlap ratio over the packing's last 0.1 s
};

StiffPoint run_stiffness(const Options& o, double k, double until, double averaging) {
  StiffPoint p;
  p.k = k;
  p.tc = contact_duration(k, paper_particle_mass());
  p.dt = p.tc / 9.0;
  Settings bed = bed_scene(o, {"contact.stiffness=" + num(k), "time.dt=" + num(p.dt)});
  bed.diagnostics.averaging_start = averaging;
  // The packing, as `packed` placement would make it, kept in the study's folder (its state
  // written before the point is stored: a packing read back has its state there).
  const Settings pk = packing_settings_for(bed);
  const std::string state = fs::absolute(fs::path(o.out) / ("packed-" + num(k) + ".state")).string();
  nlohmann::json what = run_definition("packing", pk, pk.time.end);
  what["state"] = state;
  p.packing = point_run_from_json(stored_point(o, what, fs::exists(state), [&] {
    PointRun run;
    const auto start = std::chrono::steady_clock::now();
    try {
      Simulation sim(pk);
      RunOptions opt;
      opt.until = pk.time.end;
      run.result = run_to_end(o, sim, opt);
      sim.save_state(state);
      run.ok = true;
    } catch (const SimulationFailure& e) {
      run.error = std::string("packing: ") + e.what();
      run.kind = failure_kind(e.what());
    }
    run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return point_run_json(run);
  }));
  if (!p.packing.ok) {
    p.bed.error = "not run: the packing failed";
    p.bed.kind = p.packing.kind;
    return p;
  }
  p.rest_overlap = 0.0;
  for (const auto& row : p.packing.result.rows)
    if (row.t > pk.time.end - 0.1) p.rest_overlap = std::max(p.rest_overlap, row.max_overlap_ratio);
  bed.particles.placement = Placement::State;
  bed.particles.state_file = state;
  p.bed = run_point(o, bed, until);
  return p;
}

// What the study measured: both springs, each packed and then run as the jetted bed.
struct Stiffness {
  Size size = Size::Full;
  double until = 0.0, averaging = 0.0;  // s, the bed's run and where its mean starts
  std::vector<StiffPoint> pts;          // the paper's 50,000 N/m, then Tsuji's 800 N/m
};

Stiffness measure(const Options& o) {
  Stiffness m;
  m.size = o.size;
  const bool tiny = o.size == Size::Tiny;
  m.until = tiny ? 0.4 : 1.5;
  m.averaging = tiny ? 0.2 : 0.5;
  const std::vector<double> ks = {50000.0, 800.0};
  m.pts = RunPool(o.workers).map<StiffPoint>(ks.size(), [&](std::size_t i) {
    StiffPoint p = run_stiffness(o, ks[i], m.until, m.averaging);
    if (o.log) {
      o.log("  kappa = " + num(p.k) + " N/m: " +
            (p.bed.ok ? fmt("max overlap %.3g %%",
                            100.0 * json_number(p.bed.result.summary, "max_overlap_ratio"))
                      : "failed: " + p.bed.error));
    }
    return p;
  });
  return m;
}

Table table(const Stiffness& m) {
  Table t({"stiffness_n_m", "contact_duration_s", "dt_s", "packing_bed_height_m",
           "packing_solid_fraction", "packing_max_overlap_ratio_at_rest",
           "packing_cost_wall_s_per_sim_s", "dp_mean_pa", "dp_std_pa", "dp_max_pa",
           "bed_weight_per_area_pa", "max_overlap_ratio", "max_overlap_ratio_after_startup",
           "dp_dominant_period_s", "dp_peak_period_s", "dp_cycle", "bed_height_end_m", "cost_wall_s_per_sim_s",
           "cost_cpu_s_per_sim_s", "particle_steps_per_s", "us_per_step", "simple_iterations_mean",
           "sim_time_s", "averaging_start_s", "status", "failure_kind", "failure"});
  for (const auto& p : m.pts) {
    const auto& pj = p.packing.result.summary;
    const auto& bj = p.bed.result.summary;
    const bool ok = p.packing.ok && p.bed.ok;
    t.add({num(p.k), num(p.tc), num(p.dt),
           num(p.packing.ok ? json_number(pj, "bed_height_m") : NAN),
           num(p.packing.ok ? json_number(pj, "solid_fraction") : NAN), num(p.rest_overlap),
           num(p.packing.ok ? json_number(pj, "wall_s_per_sim_s") : NAN),
           num(ok ? json_number(bj, "dp_mean_pa") : NAN),
           num(ok ? json_number(bj, "dp_std_pa") : NAN),
           num(ok ? json_number(bj, "dp_max_pa") : NAN),
           num(ok ? json_number(bj, "bed_weight_per_area_pa") : NAN),
           num(ok ? json_number(bj, "max_overlap_ratio") : NAN),
           num(ok ? json_number(bj, "max_overlap_ratio_after_startup") : NAN),
           num(ok ? json_number(bj, "dp_dominant_period_s") : NAN),
           num(ok ? json_number(bj, "dp_peak_period_s") : NAN),
           ok ? bj.value("dp_cycle", std::string()) : std::string(),
           num(ok ? json_number(bj, "bed_height_m") : NAN),
           num(ok ? json_number(bj, "wall_s_per_sim_s") : NAN),
           num(ok ? p.bed.cpu / m.until : NAN),
           num(ok ? json_number(bj, "particle_steps_per_s") : NAN),
           num(ok ? 1e6 * json_number(bj, "wall_time_s") / json_number(bj, "steps") : NAN),
           num(ok ? json_number(bj, "simple_iterations_mean") : NAN), num(m.until),
           num(m.averaging), ok ? "ok" : "failed", ok ? "" : p.bed.kind, ok ? "" : p.bed.error},
          !ok);
  }
  return t;
}

std::vector<std::string> charts(const Stiffness& m, const std::string& dir) {
  chart::Chart ov, dp;
  ov.title = "Maximum overlap ratio in the jetted bed";
  ov.x.label = "time (s)";
  ov.y.label = "max overlap ratio (%)";
  ov.y.log = true;
  dp.title = "Bed pressure drop";
  dp.x.label = "time (s)";
  dp.y.label = "dp (Pa)";
  double weight = NAN;
  for (std::size_t i = 0; i < m.pts.size(); ++i) {
    if (!m.pts[i].bed.ok) continue;
    chart::Series a, b;
    a.label = b.label = "kappa = " + num(m.pts[i].k) + " N/m, dt = " + fmt("%.3g s", m.pts[i].dt);
    a.width = b.width = 1.2;
    for (const auto& row : m.pts[i].bed.result.rows) {
      a.x.push_back(row.t);
      a.y.push_back(100.0 * row.max_overlap_ratio);
      b.x.push_back(row.t);
      b.y.push_back(row.dp);
    }
    ov.series.push_back(a);
    dp.series.push_back(b);
    weight = json_number(m.pts[i].bed.result.summary, "bed_weight_per_area_pa");
  }
  ov.hlines.push_back(
      {1.0, "1 % (the paper's Fig. 15 after start-up)", {150, 150, 150}, true, 1.0});
  if (std::isfinite(weight))
    dp.hlines.push_back({weight, "bed weight / area", {90, 90, 90}, true, 1.5});
  return {write_grid(dir, "stiffness.png", {ov, dp}, 2, 800, 520,
                     "Stiff (paper) against soft (Tsuji) springs, each at t_c / 9")};
}

std::string findings(const Stiffness& m) {
  std::ostringstream md;
  md << "Each spring at its own step t_c / 9, t_c = pi sqrt(m / kappa) (sphere-wall). The packing "
     << "falls for " << bed_scene(m.size).particles.packing_time << " s in still air; the bed then "
     << "runs " << m.until << " s at 2.8 m/s (jet), averages from " << m.averaging << " s"
     << (m.size == Size::Tiny ? " (tiny size: a bed of 300 particles 0.06 m wide)"
                              : " (the paper's bed; runs shortened from the paper's seconds "
                                "to keep the study at minutes)")
     << ".\n\n| kappa (N/m) | dt (s) | packed height (m) | solid fraction | overlap at rest | "
        "max overlap | max overlap after start-up | dp mean (Pa) | dp std (Pa) | dp cycle (regular: period) | "
        "cost (CPU s / sim s) | cost (wall s / sim s) | us per step (wall) | SIMPLE iterations per "
        "gas step |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& p : m.pts) {
    const auto& pj = p.packing.result.summary;
    const auto& bj = p.bed.result.summary;
    md << "| " << num(p.k) << " | " << fmt("%.3g", p.dt) << " | "
       << (p.packing.ok ? fmt("%.4f", json_number(pj, "bed_height_m")) : "failed") << " | "
       << (p.packing.ok ? fmt("%.3f", json_number(pj, "solid_fraction")) : "-") << " | "
       << fmt("%.3g %%", 100.0 * p.rest_overlap) << " | ";
    if (p.bed.ok)
      md << fmt("%.3g %%", 100.0 * json_number(bj, "max_overlap_ratio")) << " | "
         << fmt("%.3g %%", 100.0 * json_number(bj, "max_overlap_ratio_after_startup")) << " | "
         << fmt("%.0f", json_number(bj, "dp_mean_pa")) << " | "
         << fmt("%.0f", json_number(bj, "dp_std_pa")) << " | "
         << (std::isfinite(json_number(bj, "dp_dominant_period_s"))
                 ? fmt("%.3g s", json_number(bj, "dp_dominant_period_s"))
                 : fmt("none (peak %.3g s)", json_number(bj, "dp_peak_period_s")))
         << " | "
         << fmt("%.3g", p.bed.cpu / m.until) << " | "
         << fmt("%.3g", json_number(bj, "wall_s_per_sim_s")) << " | "
         << fmt("%.0f", 1e6 * json_number(bj, "wall_time_s") / json_number(bj, "steps")) << " | "
         << fmt("%.1f", json_number(bj, "simple_iterations_mean")) << " |\n";
    else
      md << "failed: " << p.bed.error << " | | | | | | | | |\n";
  }
  return md.str();
}

std::string advice(const Stiffness& m) {
  std::ostringstream adv;
  const StiffPoint& stiff = m.pts[0];
  const StiffPoint& soft = m.pts[1];
  if (stiff.bed.ok && soft.bed.ok) {
    const auto& sj = stiff.bed.result.summary;
    const auto& fj = soft.bed.result.summary;
    const double o_s = json_number(sj, "max_overlap_ratio_after_startup"),
                 o_f = json_number(fj, "max_overlap_ratio_after_startup");
    const double c_s = stiff.bed.cpu / m.until, c_f = soft.bed.cpu / m.until;
    adv << "Keep the paper's **50,000 N/m** for results: after start-up its overlaps stay at "
        << fmt("%.2g %%", 100.0 * o_s) << " of a diameter against " << fmt("%.2g %%", 100.0 * o_f)
        << " with 800 N/m, whose bed sits "
        << fmt("%.1f %%",
               100.0 * (1.0 - json_number(soft.packing.result.summary, "bed_height_m") /
                                  json_number(stiff.packing.result.summary, "bed_height_m")))
        << " lower when packed and whose contacts last " << fmt("%.1f", soft.tc / stiff.tc)
        << " times longer (collisions are no longer instantaneous beside the gas time scales: "
           "the paper's argument). The soft spring is "
        << fmt("%.1f", c_s / c_f)
        << " times cheaper per simulated second (CPU time), so it is fit for quick looks "
           "(teaching, previews) where overlaps of that size are acceptable, not for dp or "
           "overlap figures.";
  } else {
    adv << "One of the runs failed (" << (stiff.bed.ok ? soft.bed.error : stiff.bed.error)
        << "); the paper's 50,000 N/m is the one to keep: a spring soft enough to fail here "
           "cannot hold the bed's weight at small overlap.";
  }
  return adv.str();
}

}  // namespace

Report stiffness_study(const Options& o) {
  return run_steps<Stiffness>(o, {measure, table, charts, findings, advice});
}

}  // namespace fluidbed::app::study
