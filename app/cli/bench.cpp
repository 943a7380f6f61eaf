// fluidbed bench: the speed of a scene (default: packing) and where a step's time goes, in
// bench.json (see README.md, "Speed"); `--peer liggghts` is cli/bench_peer.cpp.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "run/packed_bed.hpp"
#include "scene/scene_loader.hpp"
#include "sim/simulation.hpp"

namespace fluidbed::app {
namespace {

// Peak resident memory of this process (kB), from /proc (0 where unavailable).
long peak_memory_kb() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      long kb = 0;
      status >> kb;
      return kb;
    }
    status.ignore(1 << 20, '\n');
  }
  return 0;
}

}  // namespace

int bench_command(const RunArgs& a) {
  const std::string scene = a.scene.empty() ? asset_dir() + "/scenes/packing.toml" : a.scene;
  Settings s = load_scene(scene, a.overrides);
  s.threads = a.threads;
  prepare_packed_bed(s);
  Simulation sim(s);
  const double until = a.until >= 0.0 ? a.until : s.time.end;
  const RunResult r = run_with_progress(sim, until);
  const auto& j = r.summary;
  const PhaseTimes& times = sim.dem().phase_times();
  nlohmann::json split = nlohmann::json::object();
  const double wall = j["wall_time_s"].get<double>();
  for (int k = 0; k < static_cast<int>(Phase::Count); ++k) {
    const double sec = times.seconds(static_cast<Phase>(k));
    split[phase_name(static_cast<Phase>(k))] = {{"seconds", sec}, {"share", wall > 0 ? sec / wall : 0.0}};
  }
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
      {"threads", sim.dem().threads()},
      {"split", split},
      {"peak_memory_kb", peak_memory_kb()},
      {"neighbour_list_builds", sim.dem().neighbours().builds()},
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
  std::printf("threads             %d\n", sim.dem().threads());
  std::printf("peak memory         %.1f MB\n", static_cast<double>(peak_memory_kb()) / 1024.0);
  std::printf("time split:\n");
  for (int k = 0; k < static_cast<int>(Phase::Count); ++k) {
    const double sec = times.seconds(static_cast<Phase>(k));
    std::printf("  %-19s %8.3f s  %5.1f %%  %8.2f us/step\n", phase_name(static_cast<Phase>(k)), sec,
                wall > 0 ? 100.0 * sec / wall : 0.0,
                1e6 * sec / std::max(1.0, j["steps"].get<double>()));
  }
  std::printf("wrote %s/bench.json\n", out.c_str());
  return 0;
}

}  // namespace fluidbed::app
