// fluidbed sweep: the paper's Fig. 6, both branches, and U_mf from the decreasing one.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "output/plots.hpp"
#include "run/ensemble.hpp"
#include "run/sweep.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "studies/study.hpp"

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

// How the sweep was started, kept in DIR/sweep.json for `sweep --resume DIR`.
nlohmann::json sweep_command_json(const SweepArgs& a) {
  return {{"scene", std::filesystem::absolute(a.scene).lexically_normal().string()},
          {"overrides", a.overrides},
          {"velocities", a.velocities},
          {"run_time_s", a.run_time},
          {"averaging_start_s", a.averaging_start},
          {"threads", a.threads},
          {"seeds", a.seeds}};
}

// `sweep --resume DIR`: the sweep's arguments from DIR/sweep.json; only --threads (which changes
// no result) may be given beside it.
SweepArgs resumed_sweep_args(const SweepArgs& given) {
  const std::string head = "cannot resume " + given.resume + ": ";
  if (given.options_given)
    throw InputError(head + "a resumed sweep takes its scene and options from DIR/sweep.json "
                            "(give only --resume DIR and, if wanted, --threads)");
  check_resume_out(given.out, given.resume, head, "sweep");
  const nlohmann::json j = read_sweep_identity(given.resume);
  SweepArgs a = given;
  a.out = given.resume;
  try {
    const nlohmann::json& c = j.at("command");
    a.scene = c.at("scene").get<std::string>();
    a.overrides = c.at("overrides").get<std::vector<std::string>>();
    a.velocities = c.at("velocities").get<std::string>();
    a.run_time = c.at("run_time_s").get<double>();
    a.averaging_start = c.at("averaging_start_s").get<double>();
    a.seeds = c.at("seeds").get<std::string>();
    if (!given.threads_given) a.threads = c.at("threads").get<int>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + "its sweep.json does not say how the sweep was started");
  }
  return a;
}

SweepOptions sweep_options(const SweepArgs& a) {
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
  o.resume = !a.resume.empty();
  o.stop = [] { return InterruptGuard::received() != 0; };
  o.command = sweep_command_json(a);
  return o;
}

}  // namespace

// `sweep --seeds`: one sweep per packing, one after another, each with its runs side by side
// (--threads), into DIR/seeds/S/ (each sweep's usual files); in DIR the ensemble's summary.json
// (run/ensemble.hpp: umf_m_s and every other number as {mean, std, min, max, n}), sweep.csv
// (the mean dp over the seeds at each velocity of each branch, with its spread) and sweep.png
// (each seed's branches faint, the means bold, U_mf's mean +- one standard deviation).
static int sweep_ensemble(const SweepArgs& a) {
  Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  check_seeded_start(s);
  const std::vector<std::uint64_t> seeds = parse_seeds(a.seeds, lattice_seed(s));
  const SweepOptions base = sweep_options(a);
  namespace fs = std::filesystem;
  for (const std::uint64_t seed : seeds) {  // a refused resume leaves the folder as it was
    SweepOptions o = base;
    o.out_dir = (fs::path(base.out_dir) / "seeds" / std::to_string(seed)).string();
    check_sweep_resume(with_seed(s, seed), o);
  }
  fs::create_directories(base.out_dir);
  fs::remove(fs::path(base.out_dir) / "summary.json");  // only a finished ensemble has one
  if (!base.resume) {
    const nlohmann::json top = {{"format", 1}, {"command", base.command}};
    write_file_atomically((fs::path(base.out_dir) / "sweep.json").string(),
                          [&](std::ostream& out) { out << top.dump(2) << "\n"; });
  }
  const InterruptGuard interrupts;
  std::vector<SweepResult> results;
  std::vector<nlohmann::json> summaries;
  for (const std::uint64_t seed : seeds) {
    SweepOptions o = base;
    o.out_dir = (fs::path(base.out_dir) / "seeds" / std::to_string(seed)).string();
    const std::string tag = "seed " + std::to_string(seed) + ": ";
    o.log = [tag](const std::string& line) {
      std::printf("%s%s\n", tag.c_str(), line.c_str());
      std::fflush(stdout);
    };
    fs::create_directories(o.out_dir);
    results.push_back(run_sweep(with_seed(s, seed), o));
    if (results.back().interrupted) {
      say_interrupted("fluidbed sweep --resume " + base.out_dir);
      return 130;
    }
    write_sweep_outputs(results.back(), o, s.scene.name);
    summaries.push_back(sweep_summary(results.back(), o, s.scene.name));
    const UmfFit& f = results.back().umf;
    if (f.ok)
      std::printf("%sU_mf = %.3f m/s\n", tag.c_str(), f.umf);
    else
      std::printf("%sU_mf not found: %s\n", tag.c_str(), f.why.c_str());
  }
  nlohmann::json summary = ensemble_summary(summaries, seeds);
  // The ensemble's curve: at each velocity of each branch, dp over the seeds whose run finished.
  std::string csv = "branch,u_superficial,dp_mean,dp_std_over_seeds,dp_min,dp_max,seeds_ok\n";
  for (const char* branch : {"up", "down"}) {
    std::vector<double> us;
    for (const auto& r : results)
      for (const auto& p : std::string(branch) == "up" ? r.up : r.down)
        if (std::find(us.begin(), us.end(), p.u) == us.end()) us.push_back(p.u);
    std::sort(us.begin(), us.end());
    for (double u : us) {
      std::vector<nlohmann::json> at;
      for (const auto& r : results)
        for (const auto& p : std::string(branch) == "up" ? r.up : r.down)
          if (p.u == u && p.ok) at.push_back({{"dp", p.dp_mean}});
      char line[256];
      if (at.empty()) {
        std::snprintf(line, sizeof line, "%s,%.4f,,,,,0\n", branch, u);
      } else {
        const nlohmann::json e = ensemble_statistics(at)["dp"];
        char sd[32] = "";  // empty with one seed
        if (e["std"].is_number()) std::snprintf(sd, sizeof sd, "%.6g", e["std"].get<double>());
        std::snprintf(line, sizeof line, "%s,%.4f,%.6g,%s,%.6g,%.6g,%zu\n", branch, u,
                      e["mean"].get<double>(), sd, e["min"].get<double>(), e["max"].get<double>(),
                      at.size());
      }
      csv += line;
    }
  }
  const fs::path dir(base.out_dir);
  write_file_atomically((dir / "sweep.csv").string(), [&](std::ostream& out) { out << csv; });
  write_file_atomically((dir / "summary.json").string(),
                        [&](std::ostream& out) { out << summary.dump(2) << "\n"; });
  const nlohmann::json& e = summary["ensemble"];
  plot_sweep_ensemble((dir / "sweep.png").string(), results,
                      e.contains("umf_m_s") ? e["umf_m_s"] : nlohmann::json(nullptr), s.scene.name);
  if (e.contains("umf_m_s"))
    std::printf("U_mf (m/s) over %zu seeds: %s\n", seeds.size(),
                ensemble_line(e["umf_m_s"], "%.3f").c_str());
  else
    std::printf("U_mf not found in any seed's sweep\n");
  std::printf("wrote %s/summary.json, sweep.csv, sweep.png and seeds/S/\n", base.out_dir.c_str());
  return 0;
}

void write_sweep_outputs(const SweepResult& r, const SweepOptions& o, const std::string& scene) {
  std::string csv = "branch,u_superficial,dp_mean,dp_std,status,wall_time_s,failure\n";
  char line[256];
  auto add = [&](const SweepPoint& p) {
    const bool run = p.ok || p.error.rfind("not run", 0) != 0;
    std::snprintf(line, sizeof line, "%s,%.4f,%.6g,%.6g,%s,%.3f,", p.branch.c_str(), p.u,
                  p.ok ? p.dp_mean : 0.0, p.ok ? p.dp_std : 0.0,
                  p.ok ? "ok" : run ? "failed" : "not_run", p.wall_time);
    csv += line;
    csv += study::csv_text(p.error) + "\n";
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

int sweep_command(const SweepArgs& given) {
  SweepArgs a = given;
  if (!given.resume.empty())
    a = resumed_sweep_args(given);
  else if (a.scene.empty())
    throw InputError("sweep: give a scene file (fluidbed sweep SCENE.toml) or --resume DIR");
  if (!a.seeds.empty()) return sweep_ensemble(a);
  const Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  const SweepOptions o = sweep_options(a);
  check_sweep_resume(s, o);  // a refused resume leaves the folder as it was
  std::filesystem::create_directories(o.out_dir);
  std::filesystem::remove(std::filesystem::path(o.out_dir) / "summary.json");  // only a finished sweep has one
  const InterruptGuard interrupts;
  const SweepResult r = run_sweep(s, o);
  if (r.interrupted) {
    say_interrupted("fluidbed sweep --resume " + o.out_dir);
    return 130;
  }
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
