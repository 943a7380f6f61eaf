// fluidbed sweep: the paper's Fig. 6, both branches, and U_mf from the decreasing one.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "studies/study.hpp"
#include "output/plots.hpp"
#include "run/sweep.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

namespace fluidbed::app {
namespace {

std::vector<double> parse_velocities(const std::string& list) {
  std::vector<double> v;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError("--velocities: \"" + item + "\" is not a number (expected e.g. 0.5,1.0,1.5)");
    }
  }
  return v;
}

}  // namespace

void write_sweep_outputs(const SweepResult& r, const SweepOptions& o, const std::string& scene) {
  std::string csv = "branch,u_superficial,dp_mean,dp_std,status,wall_time_s,failure\n";
  char line[256];
  nlohmann::json points = nlohmann::json::array();
  auto add = [&](const SweepPoint& p) {
    const bool run = p.ok || p.error.rfind("not run", 0) != 0;
    std::snprintf(line, sizeof line, "%s,%.4f,%.6g,%.6g,%s,%.3f,", p.branch.c_str(), p.u,
                  p.ok ? p.dp_mean : 0.0, p.ok ? p.dp_std : 0.0,
                  p.ok ? "ok" : run ? "failed" : "not_run", p.wall_time);
    csv += line;
    csv += study::csv_text(p.error) + "\n";
    points.push_back({{"branch", p.branch}, {"u_superficial", p.u}, {"ok", p.ok},
                      {"dp_mean", p.dp_mean}, {"dp_std", p.dp_std}, {"error", p.error},
                      {"wall_time_s", p.wall_time}});
  };
  for (const auto& p : r.up) add(p);
  for (const auto& p : r.down) add(p);
  const std::filesystem::path dir(o.out_dir);
  write_file_atomically((dir / "sweep.csv").string(), [&](std::ostream& out) { out << csv; });

  nlohmann::json j;
  j["scene"] = scene;
  j["umf_m_s"] = r.umf.ok ? nlohmann::json(r.umf.umf) : nlohmann::json(nullptr);
  j["umf_method"] =
      "decreasing branch (with the top run): least-squares line through the defluidized points "
      "and the mean of the fluidized plateau, split where the total squared error is least; "
      "U_mf is where the line reaches the plateau";
  j["umf_fit"] = {{"ok", r.umf.ok},
                  {"plateau_pa", r.umf.plateau},
                  {"intercept_pa", r.umf.intercept},
                  {"slope_pa_s_per_m", r.umf.slope},
                  {"low_points", r.umf.low_points},
                  {"high_points", r.umf.high_points},
                  {"rms_residual_pa", r.umf.rms_residual},
                  {"why", r.umf.why}};
  j["bed_weight_per_area_pa"] = r.bed_weight_per_area;
  j["run_time_s"] = o.run_time;
  j["averaging_start_s"] = o.averaging_start;
  j["threads"] = o.threads;
  j["wall_time_s"] = r.wall_time;
  j["points"] = points;
  write_file_atomically((dir / "summary.json").string(),
                        [&](std::ostream& out) { out << j.dump(2) << "\n"; });
  plot_sweep((dir / "sweep.png").string(), r, scene);
}

int sweep_command(const SweepArgs& a) {
  const Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  SweepOptions o;
  if (!a.velocities.empty()) o.velocities = parse_velocities(a.velocities);
  o.run_time = a.run_time;
  o.averaging_start = a.averaging_start;
  o.threads = a.threads;
  o.out_dir = a.out.empty() ? "out/sweep" : a.out;
  o.log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  std::filesystem::create_directories(o.out_dir);
  const SweepResult r = run_sweep(s, o);
  write_sweep_outputs(r, o, s.scene.name);
  if (r.umf.ok)
    std::printf("U_mf = %.3f m/s (plateau %.0f Pa; bed weight per area %.0f Pa)\n", r.umf.umf,
                r.umf.plateau, r.bed_weight_per_area);
  else
    std::printf("U_mf not found: %s\n", r.umf.why.c_str());
  std::printf("wrote %s/sweep.csv, sweep.png and summary.json (%.0f s)\n", o.out_dir.c_str(),
              r.wall_time);
  return 0;
}

}  // namespace fluidbed::app
