// Study 6: which fluid force the particles feel (model.md 2.1). Model A (drag and -V grad p, the
// default) against the paper's printed form (drag alone): for each, a velocity sweep (both
// branches, U_mf from the decreasing one, the plateau against the bed weight per area), the
// model's U_mf on the fixed bed, and the bubbling at 2.8 m/s (dp's fluctuation and period).
// Both start from the same packed bed.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.hpp"
#include "core/threads.hpp"
#include "output/plots.hpp"
#include "output/sweep_outputs.hpp"
#include "run/packed_bed.hpp"
#include "run/velocity_sweep.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace {
namespace fs = std::filesystem;

struct FormResult {
  bool model_a = true;
  SweepResult sweep;
  SweepOptions options;
  double fixed_umf = NAN;
  std::string fixed_error;
  nlohmann::json at28;           // summary of the increasing run nearest 2.8 m/s
  double at28_u = NAN;
  std::vector<double> t28, dp28;  // its dp against time
};

std::string label(bool a) { return a ? "model A (drag + pressure gradient)" : "printed form (drag alone)"; }

void read_run(FormResult& f) {
  // The increasing branch's run nearest 2.8 m/s: its summary and dp against time.
  const SweepPoint* best = nullptr;
  for (const auto& p : f.sweep.up)
    if (p.ok && (!best || std::fabs(p.u - 2.8) < std::fabs(best->u - 2.8))) best = &p;
  if (!best) return;
  f.at28_u = best->u;
  char name[64];
  std::snprintf(name, sizeof name, "up-%.3f", best->u);
  const fs::path dir = fs::path(f.options.out_dir) / "runs" / name;
  std::ifstream sj(dir / "summary.json");
  if (sj) f.at28 = nlohmann::json::parse(sj, nullptr, false);
  std::ifstream ts(dir / "timeseries.csv");
  std::string line;
  std::getline(ts, line);
  while (std::getline(ts, line)) {
    std::stringstream in(line);
    std::string a, b;
    std::getline(in, a, ',');
    std::getline(in, b, ',');
    f.t28.push_back(std::stod(a));
    f.dp28.push_back(std::stod(b));
  }
}

// What the study measured: for model A and the printed form, a sweep, the fixed bed's U_mf and the
// run nearest 2.8 m/s.
std::vector<FormResult> measure(const Options& o) {
  const bool tiny = o.size == Size::Tiny;
  Settings bed = bed_scene(o);
  if (o.log) o.log("packed bed (cached after the first time)");
  const std::string packed = packed_bed_state(bed, o.log);
  bed.particles.placement = Placement::State;
  bed.particles.state_file = packed;
  std::vector<FormResult> forms(2);
  for (int k = 0; k < 2; ++k) {
    FormResult& f = forms[static_cast<std::size_t>(k)];
    f.model_a = k == 0;
    Settings s = bed;
    s.coupling.pressure_gradient_force = f.model_a;
    // Model A's full sweep stops at 3.6 m/s: at 4 m/s (jet 60 m/s) it blows particles out of the
    // open top of the 0.9 m column, a failed top run that would leave the decreasing branch
    // without a start. The printed form needs 4.5 m/s to reach its plateau.
    f.options.velocities =
        tiny ? std::vector<double>{1.0, 2.0, 3.0, 4.0}
        : f.model_a ? std::vector<double>{1.0, 1.5, 2.0, 2.4, 2.8, 3.2, 3.6}
                    : std::vector<double>{1.0, 1.5, 2.0, 2.4, 2.8, 3.2, 3.6, 4.0, 4.5};
    f.options.run_time = tiny ? 0.25 : 1.0;
    f.options.averaging_start = tiny ? 0.1 : 0.5;
    f.options.threads = resolve_threads(o.workers);
    f.options.out_dir = (fs::path(o.out) / (f.model_a ? "sweep-model-a" : "sweep-printed")).string();
    f.options.log = [&](const std::string& line) {
      if (o.log) o.log("  " + std::string(f.model_a ? "model A: " : "printed: ") + line);
    };
    // Resumed with the study: the sweep's own resume (its finished runs read back, a stopped
    // run continued from its checkpoint).
    f.options.resume = o.resume && fs::exists(fs::path(f.options.out_dir) / "sweep.json");
    f.options.stop = o.stop;
    fs::create_directories(f.options.out_dir);
    if (o.log) o.log("sweep, " + label(f.model_a));
    stop_if_asked(o);
    f.sweep = run_sweep(s, f.options);
    if (f.sweep.interrupted) throw Interrupted();
    write_sweep_outputs(f.sweep, f.options, label(f.model_a));
    read_run(f);
    try {
      Settings fixed = s;
      fixed.particles.frozen = true;
      fixed.inlet.kind = InletKind::Uniform;
      double dp = 0.0;
      f.fixed_umf = f.model_a ? fixed_bed_umf(o, fixed, 1.5, 2.3, 0.03, dp)
                              : fixed_bed_umf(o, fixed, 2.3, 4.5, 0.03, dp);
    } catch (const SimulationFailure& e) {
      f.fixed_error = e.what();
    }
  }
  return forms;
}

Table table(const std::vector<FormResult>& forms) {
  Table t({"model", "pressure_gradient_force", "branch", "u_superficial", "dp_mean_pa", "dp_std_pa",
           "dp_over_weight", "bed_weight_per_area_pa", "umf_sweep_m_s", "umf_fixed_bed_m_s",
           "plateau_pa", "wall_time_s", "status", "failure_kind", "failure"});
  for (const auto& f : forms) {
    auto add = [&](const SweepPoint& p) {
      t.add({f.model_a ? "A" : "printed", f.model_a ? "true" : "false", p.branch, num(p.u),
             p.ok ? num(p.dp_mean) : "", p.ok ? num(p.dp_std) : "",
             p.ok ? num(p.dp_mean / f.sweep.bed_weight_per_area) : "",
             num(f.sweep.bed_weight_per_area), num(f.sweep.umf.ok ? f.sweep.umf.umf : NAN),
             num(f.fixed_umf), num(f.sweep.umf.ok ? f.sweep.umf.plateau : NAN), num(p.wall_time),
             p.ok ? "ok" : "failed", p.ok ? "" : failure_kind(p.error), p.error},
            !p.ok);
    };
    for (const auto& p : f.sweep.up) add(p);
    for (const auto& p : f.sweep.down) add(p);
  }
  return t;
}

std::vector<std::string> charts(const std::vector<FormResult>& forms, const std::string& dir) {
  chart::Chart sw, dt;
  sw.title = "Mean bed pressure drop against superficial velocity";
  sw.x.label = "superficial gas velocity U (m/s)";
  sw.y.label = "dp / (bed weight per area)";
  sw.x.min = 0.0;
  sw.y.min = 0.0;
  dt.title = "dp against time at U = 2.8 m/s (increasing branch)";
  dt.x.label = "time (s)";
  dt.y.label = "dp / (bed weight per area)";
  for (std::size_t k = 0; k < forms.size(); ++k) {
    const auto& f = forms[k];
    const double w = f.sweep.bed_weight_per_area;
    chart::Series up, dn, ts;
    up.label = std::string(f.model_a ? "model A" : "printed") + ", increasing U";
    dn.label = std::string(f.model_a ? "model A" : "printed") + ", decreasing U";
    up.mark = dn.mark = chart::Mark::LinePoints;
    up.colour = dn.colour = ts.colour = chart::palette(k);
    dn.dashed = true;
    dn.filled = false;
    dn.shape = chart::Shape::Square;
    for (const auto& p : f.sweep.up)
      if (p.ok) {
        up.x.push_back(p.u);
        up.y.push_back(p.dp_mean / w);
      }
    std::vector<SweepPoint> down = f.sweep.down;
    if (!f.sweep.up.empty()) down.push_back(f.sweep.up.back());
    for (const auto& p : down)
      if (p.ok) {
        dn.x.push_back(p.u);
        dn.y.push_back(p.dp_mean / w);
      }
    sw.series.push_back(up);
    sw.series.push_back(dn);
    if (f.sweep.umf.ok)
      sw.vlines.push_back({f.sweep.umf.umf,
                           std::string(f.model_a ? "A" : "printed") + fmt(": U_mf %.2f", f.sweep.umf.umf),
                           chart::palette(k), true, 1.5});
    ts.label = f.model_a ? "model A" : "printed form";
    ts.width = 1.2;
    ts.x = f.t28;
    for (double v : f.dp28) ts.y.push_back(v / w);
    dt.series.push_back(ts);
  }
  sw.hlines.push_back({1.0, "bed weight / area", {90, 90, 90}, true, 1.5});
  dt.hlines.push_back({1.0, "bed weight / area", {90, 90, 90}, true, 1.5});
  return {write_grid(dir, "model_form.png", {sw, dt}, 2, 800, 560,
                     "Model A against the paper's printed form")};
}

std::string findings(const std::vector<FormResult>& forms, Size size) {
  const bool tiny = size == Size::Tiny;
  std::ostringstream md;
  md << "Sweeps of " << forms[0].options.velocities.size() << " (model A) and "
     << forms[1].options.velocities.size() << " (printed form) velocities up to "
     << forms[0].options.velocities.back() << " and " << forms[1].options.velocities.back()
     << " m/s" << (tiny ? ", " : " (model A's bed leaves the open top of the column above that), ")
     << forms[0].options.run_time << " s each, averaged from " << forms[0].options.averaging_start
     << " s" << (tiny ? " (tiny size: 300 particles in a bed 0.06 m wide)" : " (the paper's bed; shortened from the paper's runs)")
     << "; both from the same packed bed. Bed weight per area "
     << fmt("%.0f Pa", forms[0].sweep.bed_weight_per_area) << ".\n\n"
     << "| model | U_mf, decreasing branch | U_mf, fixed bed (force = weight) | plateau / weight | "
        "dp std / mean at 2.8 m/s | dp cycle at 2.8 m/s (regular: period) | bed surface at the end |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& f : forms) {
    const double w = f.sweep.bed_weight_per_area;
    md << "| " << label(f.model_a) << " | "
       << (f.sweep.umf.ok ? fmt("%.2f m/s", f.sweep.umf.umf) : "not found: " + f.sweep.umf.why)
       << " | " << (std::isfinite(f.fixed_umf) ? fmt("%.3f m/s", f.fixed_umf) : "failed: " + f.fixed_error)
       << " | " << (f.sweep.umf.ok ? fmt("%.2f", f.sweep.umf.plateau / w) : "-") << " | "
       << fmt("%.2f", json_number(f.at28, "dp_std_pa") / json_number(f.at28, "dp_mean_pa")) << " | "
       << (std::isfinite(json_number(f.at28, "dp_dominant_period_s"))
               ? fmt("%.3g s", json_number(f.at28, "dp_dominant_period_s"))
               : fmt("none (peak %.3g s)", json_number(f.at28, "dp_peak_period_s")))
       << " | "
       << fmt("%.3f m", json_number(f.at28, "bed_height_m")) << " |\n";
  }
  md << "\nThe paper reports U_mf = 1.8 m/s (Wen-Yu 1.77) and a plateau at the bed's weight.\n";
  return md.str();
}

std::string advice(const std::vector<FormResult>& forms) {
  const auto& a = forms[0];
  const auto& p = forms[1];
  std::ostringstream adv;
  const double wa = a.sweep.bed_weight_per_area;
  adv << "Keep **model A** (`coupling.pressure_gradient_force = true`, the default). ";
  if (a.sweep.umf.ok && p.sweep.umf.ok)
    adv << "Its plateau carries " << fmt("%.2f", a.sweep.umf.plateau / wa)
        << " of the bed's weight and its U_mf is " << fmt("%.2f m/s", a.sweep.umf.umf)
        << " (paper 1.8); the printed form's plateau is " << fmt("%.2f", p.sweep.umf.plateau / wa)
        << " of the weight and its U_mf " << fmt("%.2f m/s", p.sweep.umf.umf) << ". ";
  adv << "On the fixed bed the fluid force reaches the weight at "
      << fmt("%.2f m/s", a.fixed_umf) << " with model A and at " << fmt("%.2f m/s", p.fixed_umf)
      << " with drag alone: printed as it is, the paper's pair of equations needs the drag to "
         "carry what the pressure gradient carries in a consistent model, which holds the bed down "
         "at the paper's velocities and changes how it bubbles. Use the printed form only to show "
         "that difference.";
  return adv.str();
}

}  // namespace

Report model_form_study(const Options& o) {
  const auto with_size = [&o](const std::vector<FormResult>& forms) {
    return findings(forms, o.size);
  };
  return run_steps<std::vector<FormResult>>(o, {measure, table, charts, with_size, advice});
}

}  // namespace fluidbed::app::study
