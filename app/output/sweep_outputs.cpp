// What a velocity sweep writes, alone or over several packings (output/sweep_outputs.hpp).
#include "output/sweep_outputs.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/atomic_file.hpp"
#include "core/text_format.hpp"
#include "output/plots.hpp"
#include "run/ensemble.hpp"

namespace fluidbed::app {

void write_sweep_outputs(const SweepResult& r, const SweepOptions& o, const std::string& scene) {
  std::string csv = "branch,u_superficial,dp_mean,dp_std,status,wall_time_s,failure\n";
  char line[256];
  auto add = [&](const SweepPoint& p) {
    const bool run = p.ok || p.error.rfind("not run", 0) != 0;
    std::snprintf(line, sizeof line, "%s,%.4f,%.6g,%.6g,%s,%.3f,", p.branch.c_str(), p.u,
                  p.ok ? p.dp_mean : 0.0, p.ok ? p.dp_std : 0.0,
                  p.ok  ? "ok"
                  : run ? "failed"
                        : "not_run",
                  p.wall_time);
    csv += line;
    csv += csv_field(p.error) + "\n";
  };
  for (const auto& p : r.up) add(p);
  for (const auto& p : r.down) add(p);
  const std::filesystem::path dir(o.out_dir);
  write_file_atomically((dir / "sweep.csv").string(), [&](std::ostream& out) { out << csv; });
  const nlohmann::json j = sweep_summary(r, o, scene);
  write_file_atomically((dir / "summary.json").string(),
                        [&](std::ostream& out) { out << j.dump(2) << "\n"; });
  plot_sweep((dir / "sweep.png").string(), r, scene);
}

nlohmann::json sweep_summary(const SweepResult& r, const SweepOptions& o,
                             const std::string& scene) {
  nlohmann::json points = nlohmann::json::array();
  for (const auto* branch : {&r.up, &r.down})
    for (const auto& p : *branch)
      points.push_back({{"branch", p.branch},
                        {"u_superficial", p.u},
                        {"ok", p.ok},
                        {"dp_mean", p.dp_mean},
                        {"dp_std", p.dp_std},
                        {"error", p.error},
                        {"wall_time_s", p.wall_time}});
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
  return j;
}

SweepEnsemble sweep_over_seeds(const Settings& s, const std::vector<std::uint64_t>& seeds,
                               const SweepOptions& base, const nlohmann::json& identity,
                               const std::function<void(std::uint64_t, const std::string&)>& log) {
  namespace fs = std::filesystem;
  for (const std::uint64_t seed : seeds) {  // a refused resume leaves the folder as it was
    SweepOptions o = base;
    o.out_dir = member_dir(base.out_dir, seed);
    check_sweep_resume(with_seed(s, seed), o);
  }
  SweepEnsemble e;
  e.members.resize(seeds.size());
  EnsembleJob job;
  job.dir = base.out_dir;
  job.seeds = seeds;
  job.identity = identity;
  // One sweep after another (each takes every core for its runs); a stopped one stops the rest.
  job.member = [&](std::size_t k, std::uint64_t seed,
                   const std::string& dir) -> std::optional<nlohmann::json> {
    if (e.interrupted) return std::nullopt;
    SweepOptions o = base;
    o.out_dir = dir;
    o.log = [&log, seed](const std::string& line) { log(seed, line); };
    fs::create_directories(o.out_dir);
    SweepResult r = run_sweep(with_seed(s, seed), o);
    if (r.interrupted) {
      e.interrupted = true;
      return std::nullopt;
    }
    write_sweep_outputs(r, o, s.scene.name);
    e.members[k] = std::move(r);
    return sweep_summary(e.members[k], o, s.scene.name);
  };
  const EnsembleResult r = run_ensemble(job, base.resume);
  if (!r.complete) {
    e.interrupted = true;
    return e;
  }
  e.summary = r.summary;
  e.summaries = r.summaries;
  // The ensemble's curve: at each velocity of each branch, dp over the seeds whose run finished.
  std::string csv = "branch,u_superficial,dp_mean,dp_std_over_seeds,dp_min,dp_max,seeds_ok\n";
  for (const char* branch : {"up", "down"}) {
    std::vector<double> us;
    for (const auto& m : e.members)
      for (const auto& p : std::string(branch) == "up" ? m.up : m.down)
        if (std::find(us.begin(), us.end(), p.u) == us.end()) us.push_back(p.u);
    std::sort(us.begin(), us.end());
    for (double u : us) {
      std::vector<nlohmann::json> at;
      for (const auto& m : e.members)
        for (const auto& p : std::string(branch) == "up" ? m.up : m.down)
          if (p.u == u && p.ok) at.push_back({{"dp", p.dp_mean}});
      char line[256];
      if (at.empty()) {
        std::snprintf(line, sizeof line, "%s,%.4f,,,,,0\n", branch, u);
      } else {
        const nlohmann::json st = ensemble_statistics(at)["dp"];
        char sd[32] = "";  // empty with one seed
        if (st["std"].is_number()) std::snprintf(sd, sizeof sd, "%.6g", st["std"].get<double>());
        std::snprintf(line, sizeof line, "%s,%.4f,%.6g,%s,%.6g,%.6g,%zu\n", branch, u,
                      st["mean"].get<double>(), sd, st["min"].get<double>(),
                      st["max"].get<double>(), at.size());
      }
      csv += line;
    }
  }
  const fs::path dir(base.out_dir);
  write_file_atomically((dir / "sweep.csv").string(), [&](std::ostream& out) { out << csv; });
  const nlohmann::json& st = e.summary["ensemble"];
  plot_sweep_ensemble((dir / "sweep.png").string(), e.members,
                      st.contains("umf_m_s") ? st["umf_m_s"] : nlohmann::json(nullptr),
                      s.scene.name);
  return e;
}

}  // namespace fluidbed::app
