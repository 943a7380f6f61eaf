// fluidbed bench: the speed of a scene (default: packing) and where a step's time goes, in
// bench.json (see docs/speed.md); `--peer liggghts` is cli/bench_peer.cpp.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "core/errors.hpp"
#include "run/packed_bed.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
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

// One measured run of the scene from its start.
struct Measurement {
  nlohmann::json summary;
  double phase_seconds[static_cast<int>(Phase::Count)] = {};
  std::int64_t builds = 0;
  int threads = 1;
  std::size_t particles = 0;
};

Measurement measure(const Settings& s, double until) {
  Simulation sim(s);
  const RunResult r = run_with_progress(sim, until);
  Measurement m;
  m.summary = r.summary;
  const PhaseTimes& times = sim.dem().phase_times();
  for (int k = 0; k < static_cast<int>(Phase::Count); ++k)
    m.phase_seconds[k] = times.seconds(static_cast<Phase>(k));
  m.builds = sim.dem().neighbours().builds();
  m.threads = sim.dem().threads();
  m.particles = sim.particle_count();
  return m;
}

// {median, min, max} of values (sorted copy; the median of an even count is the mean of the two
// middle values).
nlohmann::json spread(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {{"median", median}, {"min", v.front()}, {"max", v.back()}};
}

}  // namespace

int bench_command(const RunArgs& a) {
  const std::string scene = a.scene.empty() ? asset_dir() + "/scenes/packing.toml" : a.scene;
  Settings s = load_scene(scene, a.overrides);
  refuse_unsafe_scene(s);
  s.threads = a.threads;
  prepare_packed_bed(s);
  const double until = a.until >= 0.0 ? a.until : s.time.end;
  if (a.repeat < 1) throw InputError("--repeat must be at least 1");
  // The same run `repeat` times, each from the scene's start: the first is reported in full, all
  // of them as median, min and max (this machine is shared: quote medians).
  std::vector<Measurement> runs;
  for (int k = 0; k < a.repeat; ++k) runs.push_back(measure(s, until));
  const Measurement& first = runs.front();
  const auto& j = first.summary;
  nlohmann::json split = nlohmann::json::object();
  const double wall = j["wall_time_s"].get<double>();
  for (int k = 0; k < static_cast<int>(Phase::Count); ++k) {
    const double sec = first.phase_seconds[k];
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
      {"threads", first.threads},
      {"split", split},
      {"peak_memory_kb", peak_memory_kb()},
      {"memory_per_particle_kb",
       static_cast<double>(peak_memory_kb()) / static_cast<double>(std::max<std::size_t>(first.particles, 1))},
      {"neighbour_list_builds", first.builds},
  };
  if (a.repeat > 1) {
    std::vector<double> wps, pss, sps;
    nlohmann::json phases = nlohmann::json::object();
    for (const Measurement& m : runs) {
      wps.push_back(m.summary["wall_s_per_sim_s"].get<double>());
      sps.push_back(1.0 / m.summary["wall_s_per_sim_s"].get<double>());
      pss.push_back(m.summary["particle_steps_per_s"].get<double>());
    }
    for (int k = 0; k < static_cast<int>(Phase::Count); ++k) {
      std::vector<double> us;
      for (const Measurement& m : runs)
        us.push_back(1e6 * m.phase_seconds[k] / std::max(1.0, m.summary["steps"].get<double>()));
      phases[phase_name(static_cast<Phase>(k))] = spread(us);
    }
    bench["repeats"] = {{"runs", a.repeat},
                        {"wall_s_per_sim_s", spread(wps)},
                        {"sim_s_per_wall_s", spread(sps)},
                        {"particle_steps_per_s", spread(pss)},
                        {"us_per_step", phases},
                        {"wall_s_per_sim_s_each", wps}};
  }
  const std::string out = a.out.empty() ? "out/bench" : a.out;
  std::filesystem::create_directories(out);
  std::ofstream(std::filesystem::path(out) / "bench.json") << bench.dump(2) << "\n";
  std::printf("scene               %s (%zu particles, dt = %g s)\n", s.scene.name.c_str(),
              first.particles, s.time.dt);
  std::printf("simulated           %.4g s in %lld steps\n", j["sim_time_s"].get<double>(),
              static_cast<long long>(j["steps"].get<std::int64_t>()));
  std::printf("wall time           %.4g s\n", j["wall_time_s"].get<double>());
  std::printf("wall s per sim s    %.4g\n", j["wall_s_per_sim_s"].get<double>());
  std::printf("sim s per wall s    %.4g\n", bench["sim_s_per_wall_s"].get<double>());
  std::printf("particle-steps/s    %.4g\n", j["particle_steps_per_s"].get<double>());
  std::printf("threads             %d\n", first.threads);
  std::printf("peak memory         %.1f MB\n", static_cast<double>(peak_memory_kb()) / 1024.0);
  std::printf("time split:\n");
  for (int k = 0; k < static_cast<int>(Phase::Count); ++k) {
    const double sec = first.phase_seconds[k];
    std::printf("  %-19s %8.3f s  %5.1f %%  %8.2f us/step\n", phase_name(static_cast<Phase>(k)), sec,
                wall > 0 ? 100.0 * sec / wall : 0.0,
                1e6 * sec / std::max(1.0, j["steps"].get<double>()));
  }
  if (a.repeat > 1) {
    const auto& rp = bench["repeats"];
    auto line = [&](const char* what, const nlohmann::json& v) {
      std::printf("  %-19s median %.4g  min %.4g  max %.4g\n", what, v["median"].get<double>(),
                  v["min"].get<double>(), v["max"].get<double>());
    };
    std::printf("over %d runs:\n", a.repeat);
    line("wall s per sim s", rp["wall_s_per_sim_s"]);
    line("sim s per wall s", rp["sim_s_per_wall_s"]);
    line("particle-steps/s", rp["particle_steps_per_s"]);
    for (int k = 0; k < static_cast<int>(Phase::Count); ++k)
      line((std::string(phase_name(static_cast<Phase>(k))) + " us").c_str(),
           rp["us_per_step"][phase_name(static_cast<Phase>(k))]);
  }
  std::printf("wrote %s/bench.json\n", out.c_str());
  return 0;
}

}  // namespace fluidbed::app
