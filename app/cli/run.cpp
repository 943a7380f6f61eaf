#include "cli/commands.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>

#include "core/errors.hpp"
#include "output/frames.hpp"
#include "output/plots.hpp"
#include "run/packed_bed.hpp"
#include "run/run.hpp"
#include "scene/scene_loader.hpp"

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

RunResult run_with_progress(Simulation& sim, double until,
                            std::function<void(const Simulation&)> on_step = {}) {
  RunOptions opt;
  opt.until = until;
  opt.on_step = std::move(on_step);
  const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal) opt.progress = [until](const Simulation& s, double w) { print_progress(s, w, until); };
  RunResult r = run_simulation(sim, opt);
  if (terminal) std::fprintf(stderr, "\n");
  return r;
}

std::vector<int> parse_ids(const std::string& list, std::size_t count) {
  std::vector<int> ids;
  std::size_t pos = 0;
  while (pos <= list.size()) {
    const std::size_t comma = std::min(list.find(',', pos), list.size());
    const std::string item = list.substr(pos, comma - pos);
    char* end = nullptr;
    const long v = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v < 0 || static_cast<std::size_t>(v) >= count)
      throw InputError("--track: \"" + item + "\" is not a particle id (0 to " +
                       std::to_string(count - 1) + ")");
    ids.push_back(static_cast<int>(v));
    pos = comma + 1;
  }
  return ids;
}

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

std::string asset_dir() {
  if (const char* env = std::getenv("FLUIDBED_ASSETS")) return env;
  return FLUIDBED_ASSET_DIR;
}

int run_command(const RunArgs& a) {
  Settings s = load_scene(a.scene, a.overrides);
  s.threads = a.threads;
  const std::string out = a.out.empty() ? default_out(a.scene) : a.out;
  prepare_packed_bed(s);
  Simulation sim(s);
  std::unique_ptr<TrajectoryRecorder> tracks;
  if (a.plots) {
    std::vector<int> ids;
    if (a.track.empty()) {
      ids = nearest_particles(sim.dem().particles(), jet_region_points(s.domain.width));
    } else {
      ids = parse_ids(a.track, sim.particle_count());
    }
    tracks = std::make_unique<TrajectoryRecorder>(ids, s.diagnostics.output_interval, s.time.dt);
  }
  const double until = a.until >= 0.0 ? a.until : s.time.end;
  // Frames, video, montage, VTK: snapshots at exact times, drawn and written by a worker thread.
  std::unique_ptr<FrameOutput> pictures;
  if (const FrameOptions fo = frame_options(a.output, asset_dir()); fo.any()) {
    pictures = std::make_unique<FrameOutput>(out, fo, sim, until);
    pictures->observe(sim);  // the starting state, when it is an output time
  }
  std::function<void(const Simulation&)> on_step;
  if (pictures || tracks)
    on_step = [&](const Simulation& x) {
      if (pictures) pictures->observe(x);
      if (tracks) tracks->observe(x);
    };
  const RunResult r = run_with_progress(sim, until, on_step);
  const FrameStats picture_stats = pictures ? pictures->finish() : FrameStats{};
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
  if (pictures) report_frame_output(out, a.output, picture_stats, r.summary["wall_time_s"].get<double>());
  if (tracks) {
    const auto files = plot_run(out, r, tracks->tracks(), s.domain.width, s.domain.height, sim.has_gas());
    for (const auto& f : files) std::printf("wrote %s\n", f.c_str());
  }
  return 0;
}

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
