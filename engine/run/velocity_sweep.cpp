#include "run/velocity_sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <numbers>
#include <numeric>
#include <optional>

#include "core/atomic_file.hpp"
#include "core/binary_io.hpp"
#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "core/run_pool.hpp"
#include "run/checkpoint.hpp"
#include "run/packed_bed.hpp"
#include "run/run_folder.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {
namespace {

namespace fs = std::filesystem;

std::string point_name(const std::string& branch, double u) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s-%.3f", branch.c_str(), u);
  return buf;
}

fs::path point_dir(const SweepOptions& o, const std::string& branch, double u) {
  return fs::path(o.out_dir) / "runs" / point_name(branch, u);
}

// The particle configuration's hash at a point's start and end (the hand-over along the
// decreasing branch), kept in its finished marker's `result`.
class ConfigurationHashes : public RunOutput {
 public:
  void start(const Simulation& sim, double) override { start_ = sim.dem().configuration_hash(); }
  void restore(const std::string& folder, const Simulation&, double) override {
    const std::string p = (fs::path(folder) / "start_hash.bin").string();
    std::ifstream in = open_input_file(p, "checkpoint");
    BinarySource src(in, p);
    src(start_);
  }
  void observe(const Simulation&) override {}
  void save(const std::string& folder) override {
    std::ofstream out(fs::path(folder) / "start_hash.bin", std::ios::binary);
    BinarySink sink(out);
    sink(start_);
  }
  void finish(FinishedRun& run) override {
    run.result_record["start_hash"] = start_;
    run.result_record["end_hash"] = run.sim.dem().configuration_hash();
  }

 private:
  std::uint64_t start_ = 0;
};

// One run of the sweep in its folder (run/run_folder.hpp): from the scene's start (up) or from
// `from_state` (down). Resumed, a run that ended is read back and a stopped one continues.
SweepPoint run_point(const Settings& scene, const SweepOptions& o, const std::string& branch,
                     double u, const std::string& from_state) {
  SweepPoint pt;
  pt.branch = branch;
  pt.u = u;
  RunJob job;
  job.scene = scene;
  // Runs side by side take a core each; a lone run may use them all.
  if (o.threads > 1) job.scene.threads = 1;
  job.scene.inlet.superficial_velocity = u;
  job.scene.time.end = o.run_time;
  job.scene.diagnostics.averaging_start = o.averaging_start;
  job.scene.diagnostics.save_state.clear();
  job.start_state = from_state;
  job.started = o.command.is_object() ? o.command : nlohmann::json::object();
  job.final_state = "final.state";
  job.outputs.push_back(std::make_unique<ConfigurationHashes>());
  RunControl control;
  control.resume = o.resume;
  control.stop = o.stop;
  control.checkpoint_every = std::max(0.0, o.checkpoint_interval);
  const fs::path dir = point_dir(o, branch, u);
  const RunEnd end = run_in_folder(dir.string(), job, control);
  if (end.how == RunEnd::How::stopped) {
    pt.interrupted = true;
    return pt;
  }
  pt.resumed = end.resumed;
  pt.wall_time = end.wall;
  pt.ok = end.finished();
  pt.error = end.error;
  pt.start_hash = end.record.value("start_hash", std::uint64_t{0});
  pt.end_hash = end.record.value("end_hash", std::uint64_t{0});
  if (pt.ok) {
    pt.dp_mean = end.result.summary.value("dp_mean_pa", 0.0);
    pt.dp_std = end.result.summary.value("dp_std_pa", 0.0);
    pt.state_path = (dir / "final.state").string();
  }
  return pt;
}

}  // namespace

std::vector<double> default_sweep_velocities() {
  std::vector<double> v = {0.5, 0.8, 1.0, 1.2};
  for (int k = 14; k <= 32; ++k) v.push_back(k / 10.0);  // 1.4 ... 3.2 by 0.1
  return v;
}

double terminal_velocity(const Settings& scene) {
  constexpr double kPi = std::numbers::pi;
  const double d = scene.particles.diameter, rho_g = scene.gas.density;
  const double weight =
      (scene.particles.density - rho_g) * scene.physics.gravity * kPi * d * d * d / 6.0;
  auto excess_drag = [&](double u) {
    const double re = rho_g * u * d / scene.gas.viscosity;
    const double cd = std::pow(0.63 + 4.8 / std::sqrt(re), 2.0);
    return cd * 0.5 * rho_g * u * u * kPi * d * d / 4.0 - weight;
  };
  if (!(weight > 0.0)) return INFINITY;
  double lo = 1e-9, hi = 1e4;  // m/s: drag below the weight at lo, above it at hi
  for (int k = 0; k < 200 && hi - lo > 1e-9 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (excess_drag(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

// The paper's list (m/s, increasing) for `scene`'s particles and gas (default_sweep_velocities).
std::vector<double> scaled_for(const Settings& scene, const std::vector<double>& paper_list) {
  auto umf_of = [](const Settings& s) {
    return wen_yu_umf(s.particles.diameter, s.particles.density, s.gas.density, s.gas.viscosity,
                      s.physics.gravity);
  };
  const double umf = umf_of(scene), paper = umf_of(Settings{});
  const double scale = umf > 0.0 && paper > 0.0 ? umf / paper : 1.0;
  const double cap = 0.8 * terminal_velocity(scene);
  std::vector<double> v;
  for (double u : paper_list) {
    const double x = std::round(100.0 * u * scale) / 100.0;
    if (x > 0.0 && x < cap && (v.empty() || x > v.back())) v.push_back(x);
  }
  return v;
}

}  // namespace

std::vector<double> default_sweep_velocities(const Settings& scene) {
  return scaled_for(scene, default_sweep_velocities());
}

std::vector<double> decreasing_branch_velocities() {
  return {0.5, 0.9, 1.4, 1.7, 2.0, 2.3, 2.6, 3.0};
}

std::vector<double> decreasing_branch_velocities(const Settings& scene) {
  return scaled_for(scene, decreasing_branch_velocities());
}

namespace {

// The options as a sweep runs them: the scene's velocities when none are given, sorted, each
// once; InputError for options no sweep can run.
SweepOptions checked_options(const Settings& scene, const SweepOptions& options) {
  SweepOptions o = options;
  if (o.velocities.empty()) o.velocities = default_sweep_velocities(scene);
  if (o.out_dir.empty()) throw InputError("sweep: an output folder is needed");
  if (!scene.gas.enabled) throw InputError("sweep: the scene has no [gas] section");
  if (!(o.run_time > 0.0)) throw InputError("sweep: the run time must be positive");
  if (!(o.averaging_start >= 0.0 && o.averaging_start < o.run_time))
    throw InputError("sweep: the averaging start must lie inside the run");
  for (double u : o.velocities)
    if (!(u >= 0.0) || !std::isfinite(u)) throw InputError("sweep: velocities must be >= 0");
  std::sort(o.velocities.begin(), o.velocities.end());
  o.velocities.erase(std::unique(o.velocities.begin(), o.velocities.end()), o.velocities.end());
  if (o.velocities.size() < 2) throw InputError("sweep: needs at least two velocities");
  // Each run's folder is named by its velocity to 1 mm/s: two velocities closer than that would
  // share one folder, the second run overwriting the first's files.
  for (std::size_t k = 1; k < o.velocities.size(); ++k)
    if (point_name("up", o.velocities[k - 1]) == point_name("up", o.velocities[k])) {
      char line[256];
      std::snprintf(line, sizeof line,
                    "sweep: velocities %.6g and %.6g m/s are the same to 1 mm/s (each run's folder "
                    "is named by its velocity in mm/s); give velocities at least 1 mm/s apart",
                    o.velocities[k - 1], o.velocities[k]);
      throw InputError(line);
    }
  o.threads = std::max(1, o.threads);
  return o;
}

}  // namespace

SweepResult run_sweep(const Settings& sweep_scene, const SweepOptions& options) {
  const SweepOptions o = checked_options(sweep_scene, options);
  Settings scene = sweep_scene;

  const auto start = std::chrono::steady_clock::now();
  // Pack once before the runs share the cache.
  prepare_packed_bed(scene, o.log);
  // The folder's sweep: the same one when resumed (a folder with no sweep.json yet has nothing
  // to resume), a new one otherwise, whose runs' records and checkpoints from before are removed.
  const fs::path identity_file = fs::path(o.out_dir) / "sweep.json";
  if (o.resume && fs::exists(identity_file)) {
    check_sweep_resume(scene, o);
  } else {
    fs::create_directories(o.out_dir);
    for (const char* branch : {"up", "down"})
      for (double u : o.velocities) {
        std::error_code ec;
        fs::remove(point_dir(o, branch, u) / "status.json", ec);
        remove_checkpoint(point_dir(o, branch, u).string());
      }
    const nlohmann::json identity = sweep_identity(scene, o);
    write_file_atomically(identity_file.string(),
                          [&](std::ostream& out) { out << identity.dump(2) << "\n"; });
  }
  auto stopped = [&] { return o.stop && o.stop(); };
  const std::size_t n = o.velocities.size();
  SweepResult result;
  result.up.resize(n);
  result.down.resize(n - 1);
  std::mutex log_mutex;
  auto report = [&](const SweepPoint& p) {
    if (!o.log) return;
    char line[256];
    if (p.ok)
      std::snprintf(line, sizeof line, "%-4s U = %.3f m/s: dp = %.0f +- %.0f Pa (%.0f s%s)",
                    p.branch.c_str(), p.u, p.dp_mean, p.dp_std, p.wall_time,
                    p.resumed ? ", resumed" : "");
    else
      std::snprintf(line, sizeof line, "%-4s U = %.3f m/s: failed: %s", p.branch.c_str(), p.u,
                    p.error.c_str());
    std::lock_guard lock(log_mutex);
    o.log(line);
  };

  // The decreasing chain starts from the highest velocity whose run finishes: one worker takes
  // the increasing runs from the top down until one does, then walks the chain down, each run
  // from the lowest finished run above it (a failed run is a row with its reason, and the chain
  // goes on from the run above it). The other workers take the remaining increasing runs from the
  // bottom up. Each increasing run is claimed once (0 free, 1 running, 2 done).
  std::unique_ptr<std::atomic<int>[]> state(new std::atomic<int>[n]);
  for (std::size_t k = 0; k < n; ++k) state[k] = 0;
  auto run_up = [&](std::size_t k) {
    int expected = 0;
    if (!state[k].compare_exchange_strong(expected, 1)) return false;
    if (stopped()) {
      result.up[k].branch = "up";
      result.up[k].u = o.velocities[k];
      result.up[k].interrupted = true;
    } else {
      try {
        result.up[k] = run_point(scene, o, "up", o.velocities[k], "");
      } catch (...) {  // an InputError or a file error: the sweep ends with it (RunPool rethrows)
        result.up[k].interrupted = true;  // so that the chain, waiting on it, stops
        state[k] = 2;
        throw;
      }
      if (!result.up[k].interrupted) report(result.up[k]);
    }
    state[k] = 2;
    return true;
  };
  auto down_chain = [&] {
    std::size_t top = n;  // the highest finished increasing run
    for (std::size_t k = n; k-- > 0;) {
      if (!run_up(k))
        while (state[k].load() != 2) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (result.up[k].interrupted) return;
      if (result.up[k].ok) {
        top = k;
        break;
      }
    }
    for (std::size_t k = 0; k + 1 < n; ++k) {
      result.down[k].branch = "down";
      result.down[k].u = o.velocities[k];
    }
    if (top == n) {
      for (auto& d : result.down) d.error = "not run: no increasing run finished";
      return;
    }
    for (std::size_t k = top; k + 1 < n; ++k)
      result.down[k].error = "not run: above the highest velocity whose run finished";
    const SweepPoint* from = &result.up[top];
    for (std::size_t k = top; k-- > 0;) {
      if (stopped()) {
        result.down[k].interrupted = true;
        return;
      }
      result.down[k] = run_point(scene, o, "down", o.velocities[k], from->state_path);
      if (result.down[k].interrupted) return;
      report(result.down[k]);
      if (result.down[k].ok) from = &result.down[k];
    }
  };
  // The chain first, so that one worker walks it while the others share the increasing runs.
  std::vector<std::function<void()>> tasks = {down_chain};
  if (o.decreasing_only) {
    for (std::size_t k = 0; k + 1 < n; ++k) {
      result.up[k].branch = "up";
      result.up[k].u = o.velocities[k];
      result.up[k].error = "not run: decreasing branch only";
      state[k] = 2;  // claimed: the chain starts at the top run
    }
  } else {
    for (std::size_t k = 0; k + 1 < n; ++k) tasks.push_back([&, k] { run_up(k); });
  }
  RunPool(o.threads).run(tasks);
  for (const auto* branch : {&result.up, &result.down})
    for (const auto& p : *branch) result.interrupted = result.interrupted || p.interrupted;
  // A stopped sweep has no result: only its runs' records and checkpoints, for a resume.
  if (result.interrupted) return result;

  // Umf from the decreasing branch, with the shared top point.
  std::vector<double> us, dps;
  for (const SweepPoint& p : way_down(result))
    if (p.ok) {
      us.push_back(p.u);
      dps.push_back(p.dp_mean);
    }
  result.umf = fit_umf(us, dps);
  constexpr double kPi = std::numbers::pi;
  const double d = scene.particles.diameter;
  const double mass = scene.particles.count * scene.particles.density * kPi * d * d * d / 6.0;
  result.bed_weight_per_area =
      mass * scene.physics.gravity / (scene.domain.width * scene.domain.thickness);
  result.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

SweepOptions decreasing_branch_options(std::vector<double> velocities, double run_time,
                                       double averaging, std::string out_dir) {
  SweepOptions o;
  o.velocities = std::move(velocities);
  o.run_time = run_time;
  o.averaging_start = averaging;
  o.threads = 1;  // the chain is one run after another
  o.decreasing_only = true;
  o.out_dir = std::move(out_dir);
  return o;
}

std::vector<SweepPoint> way_down(const SweepResult& r) {
  std::vector<SweepPoint> branch = r.down;
  for (std::size_t k = r.up.size(); k-- > 0;)  // the chain's start
    if (r.up[k].ok) {
      branch.push_back(r.up[k]);
      break;
    }
  return branch;
}

nlohmann::json sweep_identity(const Settings& scene, const SweepOptions& options) {
  std::vector<double> velocities =
      options.velocities.empty() ? default_sweep_velocities(scene) : options.velocities;
  std::sort(velocities.begin(), velocities.end());
  velocities.erase(std::unique(velocities.begin(), velocities.end()), velocities.end());
  return {{"format", 1},
          {"scene_toml", to_toml(scene)},
          {"velocities_m_s", velocities},
          {"run_time_s", options.run_time},
          {"averaging_start_s", options.averaging_start},
          {"decreasing_only", options.decreasing_only},
          {"command", options.command}};
}

void check_sweep_resume(const Settings& scene, const SweepOptions& options) {
  const SweepOptions o = checked_options(scene, options);
  if (!o.resume || !fs::exists(fs::path(o.out_dir) / "sweep.json")) return;
  const nlohmann::json identity = sweep_identity(scene, o);
  const nlohmann::json was = read_sweep_identity(o.out_dir);
  const std::string head = "cannot resume " + o.out_dir + ": ";
  const std::string scene_change = first_difference(identity["scene_toml"].get<std::string>(),
                                                    was.value("scene_toml", std::string()));
  if (!scene_change.empty())
    throw InputError(head + "the scene is not the one the sweep started with (" + scene_change +
                     ")");
  nlohmann::json before = was;
  if (!before.contains("decreasing_only")) before["decreasing_only"] = false;  // older folders
  for (const char* key : {"velocities_m_s", "run_time_s", "averaging_start_s", "decreasing_only"})
    if (identity[key] != before.value(key, nlohmann::json()))
      throw InputError(head + "the sweep's " + key + " " + identity[key].dump() + " differ from " +
                       before.value(key, nlohmann::json()).dump());
}

nlohmann::json read_sweep_identity(const std::string& out_dir) {
  const fs::path file = fs::path(out_dir) / "sweep.json";
  if (!fs::is_directory(out_dir)) throw InputError(out_dir + " is not a folder");
  if (!fs::is_regular_file(file))
    throw InputError(out_dir + " holds no sweep to resume (no sweep.json)");
  try {
    std::ifstream in(file);
    nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("format").get<int>() != 1) throw InputError(file.string() + ": of another format");
    return j;
  } catch (const nlohmann::json::exception&) {
    throw InputError(file.string() + ": not a sweep's record");
  }
}

}  // namespace fluidbed
