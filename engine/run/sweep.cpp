#include "run/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <numbers>
#include <numeric>

#include "core/errors.hpp"
#include "core/run_pool.hpp"
#include "run/packed_bed.hpp"
#include "run/run.hpp"
#include "sim/checks.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {
namespace {

std::string point_name(const std::string& branch, double u) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s-%.3f", branch.c_str(), u);
  return buf;
}

// One run of the sweep: from the scene's start (up) or from `from_state` (down).
SweepPoint run_point(const Settings& scene, const SweepOptions& o, const std::string& branch,
                     double u, const std::string& from_state) {
  namespace fs = std::filesystem;
  SweepPoint pt;
  pt.branch = branch;
  pt.u = u;
  Settings s = scene;
  // Runs side by side take a core each; a lone run may use them all.
  if (o.threads > 1) s.threads = 1;
  s.inlet.superficial_velocity = u;
  s.time.end = o.run_time;
  s.diagnostics.averaging_start = o.averaging_start;
  s.diagnostics.save_state.clear();
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = fs::path(o.out_dir) / "runs" / point_name(branch, u);
  try {
    Simulation sim(s);
    if (!from_state.empty()) sim.continue_from(from_state);
    pt.start_hash = sim.dem().configuration_hash();
    const RunResult r = run_simulation(sim, RunOptions{});
    write_run_outputs(dir.string(), r);
    pt.dp_mean = r.summary.value("dp_mean_pa", 0.0);
    pt.dp_std = r.summary.value("dp_std_pa", 0.0);
    pt.end_hash = sim.dem().configuration_hash();
    pt.state_path = (dir / "final.state").string();
    sim.save_state(pt.state_path);
    pt.ok = true;
  } catch (const SimulationFailure& e) {
    pt.error = e.what();
  }
  pt.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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

std::vector<double> default_sweep_velocities(const Settings& scene) {
  auto umf_of = [](const Settings& s) {
    return wen_yu_umf(s.particles.diameter, s.particles.density, s.gas.density, s.gas.viscosity,
                      s.physics.gravity);
  };
  const double umf = umf_of(scene), paper = umf_of(Settings{});
  const double scale = umf > 0.0 && paper > 0.0 ? umf / paper : 1.0;
  const double cap = 0.8 * terminal_velocity(scene);
  std::vector<double> v;
  for (double u : default_sweep_velocities()) {
    const double x = std::round(100.0 * u * scale) / 100.0;
    if (x > 0.0 && x < cap && (v.empty() || x > v.back())) v.push_back(x);
  }
  return v;
}

SweepResult run_sweep(const Settings& sweep_scene, const SweepOptions& options) {
  SweepOptions o = options;
  Settings scene = sweep_scene;
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
  o.threads = std::max(1, o.threads);

  const auto start = std::chrono::steady_clock::now();
  // Pack once before the runs share the cache.
  prepare_packed_bed(scene, o.log);
  const std::size_t n = o.velocities.size();
  SweepResult result;
  result.up.resize(n);
  result.down.resize(n - 1);
  std::mutex log_mutex;
  auto report = [&](const SweepPoint& p) {
    if (!o.log) return;
    char line[256];
    if (p.ok)
      std::snprintf(line, sizeof line, "%-4s U = %.3f m/s: dp = %.0f +- %.0f Pa (%.0f s)",
                    p.branch.c_str(), p.u, p.dp_mean, p.dp_std, p.wall_time);
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
    result.up[k] = run_point(scene, o, "up", o.velocities[k], "");
    report(result.up[k]);
    state[k] = 2;
    return true;
  };
  auto down_chain = [&] {
    std::size_t top = n;  // the highest finished increasing run
    for (std::size_t k = n; k-- > 0;) {
      if (!run_up(k))
        while (state[k].load() != 2) std::this_thread::sleep_for(std::chrono::milliseconds(20));
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
      result.down[k] = run_point(scene, o, "down", o.velocities[k], from->state_path);
      report(result.down[k]);
      if (result.down[k].ok) from = &result.down[k];
    }
  };
  // The chain first, so that one worker walks it while the others share the increasing runs.
  std::vector<std::function<void()>> tasks = {down_chain};
  for (std::size_t k = 0; k + 1 < n; ++k) tasks.push_back([&, k] { run_up(k); });
  RunPool(o.threads).run(tasks);

  // Umf from the decreasing branch, with the shared top point.
  std::vector<double> us, dps;
  for (const auto& p : result.down)
    if (p.ok) {
      us.push_back(p.u);
      dps.push_back(p.dp_mean);
    }
  for (std::size_t k = n; k-- > 0;)  // the chain's start: the highest finished increasing run
    if (result.up[k].ok) {
      us.push_back(result.up[k].u);
      dps.push_back(result.up[k].dp_mean);
      break;
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

}  // namespace fluidbed
