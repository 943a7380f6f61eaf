#include "commands.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "core/errors.hpp"
#include "scene/scene_loader.hpp"
#include "sim/run.hpp"

namespace fluidbed::app {
namespace {

std::string default_out(const std::string& scene) {
  return (std::filesystem::path("out") / std::filesystem::path(scene).stem()).string();
}

void print_progress(const Simulation& sim, double wall, double until) {
  const double t = sim.time();
  const double steps = static_cast<double>(sim.steps());
  std::fprintf(stderr, "\r  t = %.4f / %.4f s   %.3g wall s per sim s   %.3g particle-steps/s   ",
               t, until, t > 0.0 ? wall / t : 0.0,
               wall > 0.0 ? steps * static_cast<double>(sim.particle_count()) / wall : 0.0);
  std::fflush(stderr);
}

RunResult run_with_progress(Simulation& sim, double until) {
  RunOptions opt;
  opt.until = until;
  const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal) opt.progress = [until](const Simulation& s, double w) { print_progress(s, w, until); };
  RunResult r = run_simulation(sim, opt);
  if (terminal) std::fprintf(stderr, "\n");
  return r;
}

}  // namespace

std::string asset_dir() {
  if (const char* env = std::getenv("FLUIDBED_ASSETS")) return env;
  return FLUIDBED_ASSET_DIR;
}

int run_command(const RunArgs& a) {
  const Settings s = load_scene(a.scene, a.overrides);
  const std::string out = a.out.empty() ? default_out(a.scene) : a.out;
  Simulation sim(s);
  const double until = a.until >= 0.0 ? a.until : s.time.end;
  const RunResult r = run_with_progress(sim, until);
  write_run_outputs(out, r);
  {
    std::ofstream scene_out(std::filesystem::path(out) / "scene.toml");
    scene_out << "# the scene as run, every value resolved\n" << to_toml(s);
  }
  if (!s.diagnostics.save_state.empty())
    sim.save_state((std::filesystem::path(out) / s.diagnostics.save_state).string());
  std::printf("%s: %lld steps of %zu particles to t = %.4g s in %.3g s wall (%.3g particle-steps/s)\n",
              s.scene.name.c_str(), static_cast<long long>(r.summary["steps"].get<std::int64_t>()),
              sim.particle_count(), sim.time(), r.summary["wall_time_s"].get<double>(),
              r.summary["particle_steps_per_s"].get<double>());
  std::printf("wrote %s/summary.json and %s/timeseries.csv\n", out.c_str(), out.c_str());
  return 0;
}

int bench_command(const RunArgs& a) {
  const std::string scene = a.scene.empty() ? asset_dir() + "/scenes/packing.toml" : a.scene;
  const Settings s = load_scene(scene, a.overrides);
  Simulation sim(s);
  const double until = a.until >= 0.0 ? a.until : s.time.end;
  const RunResult r = run_with_progress(sim, until);
  const auto& j = r.summary;
  nlohmann::json bench = {
      {"scene", s.scene.name},
      {"particles", j["particles"]},
      {"steps", j["steps"]},
      {"sim_time_s", j["sim_time_s"]},
      {"wall_time_s", j["wall_time_s"]},
      {"wall_s_per_sim_s", j["wall_s_per_sim_s"]},
      {"sim_s_per_wall_s", j["wall_time_s"].get<double>() > 0.0
                               ? j["sim_time_s"].get<double>() / j["wall_time_s"].get<double>()
                               : 0.0},
      {"particle_steps_per_s", j["particle_steps_per_s"]},
      {"threads", 1},
  };
  const std::string out = a.out.empty() ? "out/bench" : a.out;
  std::filesystem::create_directories(out);
  std::ofstream(std::filesystem::path(out) / "bench.json") << bench.dump(2) << "\n";
  std::printf("scene               %s (%zu particles, dt = %g s)\n", s.scene.name.c_str(),
              sim.particle_count(), s.time.dt);
  std::printf("simulated           %.4g s in %lld steps\n", j["sim_time_s"].get<double>(),
              static_cast<long long>(j["steps"].get<std::int64_t>()));
  std::printf("wall time           %.4g s\n", j["wall_time_s"].get<double>());
  std::printf("wall s per sim s    %.4g\n", j["wall_s_per_sim_s"].get<double>());
  std::printf("sim s per wall s    %.4g\n", bench["sim_s_per_wall_s"].get<double>());
  std::printf("particle-steps/s    %.4g\n", j["particle_steps_per_s"].get<double>());
  std::printf("threads             1\n");
  std::printf("wrote %s/bench.json\n", out.c_str());
  return 0;
}

}  // namespace fluidbed::app
