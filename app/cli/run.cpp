// fluidbed run: one scene to its end, summary.json and timeseries.csv; with options its frames,
// video, montage, VTK files and the paper's plots (README.md, "Pictures, video and ParaView files").
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/progress.hpp"
#include "core/errors.hpp"
#include "output/frames.hpp"
#include "output/plots.hpp"
#include "run/live_folder.hpp"
#include "run/packed_bed.hpp"
#include "run/run.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

namespace fluidbed::app {
namespace {

std::string default_out(const std::string& scene) {
  return (std::filesystem::path("out") / std::filesystem::path(scene).stem()).string();
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

}  // namespace

int run_command(const RunArgs& a) {
  Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
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
  // The folder says what the run is doing while it runs (run/live_folder.hpp), and an
  // interrupt (SIGINT, SIGTERM) stops it at the end of a step.
  LiveRunFolder live(out, s.scene.name, a.bubbles);
  {
    std::ofstream scene_out(std::filesystem::path(out) / "scene.toml");
    scene_out << "# the scene as run, every value resolved\n" << to_toml(s);
  }
  const InterruptGuard interrupts;
  RunResult r;
  try {
    r = run_with_progress(sim, until, on_step, a.bubbles, [&](const TimeseriesRow& row) { live.row(row); },
                          [] { return InterruptGuard::received() != 0; });
  } catch (const SimulationFailure& e) {
    live.failed(e.what());
    throw;
  }
  if (!r.completed) {
    const std::string why = std::string("stopped by ") + InterruptGuard::name(InterruptGuard::received());
    live.interrupted(sim.time(), why);
    std::fprintf(stderr, "interrupted at t = %.6g s (%s): the timeseries so far is in %s/timeseries.csv, no summary.json\n",
                 sim.time(), why.c_str(), out.c_str());
    return 130;
  }
  const FrameStats picture_stats = pictures ? pictures->finish() : FrameStats{};
  write_run_outputs(out, r);
  live.completed(sim.time());
  if (!s.diagnostics.save_state.empty())
    sim.save_state((std::filesystem::path(out) / s.diagnostics.save_state).string());
  std::printf("%s: %lld steps of %zu particles to t = %.4g s in %.3g s wall (%.3g particle-steps/s)\n",
              s.scene.name.c_str(), static_cast<long long>(r.summary["steps"].get<std::int64_t>()),
              sim.particle_count(), sim.time(), r.summary["wall_time_s"].get<double>(),
              r.summary["particle_steps_per_s"].get<double>());
  std::printf("wrote %s/summary.json and %s/timeseries.csv\n", out.c_str(), out.c_str());
  if (r.bubbles) {
    const auto& b = r.summary["bubbles"];
    auto num = [&](const char* k) { return b[k].is_number() ? b[k].get<double>() : 0.0; };
    std::printf("bubbles: %.2f formed per s, %.2f eruptions per s, mean D_e %.1f mm, rise %.3f m/s, "
                "regime %s; wrote %s/bubbles.csv and %s/mixing.csv\n",
                num("formed_per_s"), num("eruptions_per_s"), 1e3 * num("mean_d_eq_m"),
                num("mean_rise_velocity_m_s"), b["regime"].get<std::string>().c_str(), out.c_str(),
                out.c_str());
  }
  if (pictures) report_frame_output(out, a.output, picture_stats, r.summary["wall_time_s"].get<double>());
  if (tracks) {
    const auto files = plot_run(out, r, tracks->tracks(), s.domain.width, s.domain.height, sim.has_gas());
    for (const auto& f : files) std::printf("wrote %s\n", f.c_str());
  }
  return 0;
}

}  // namespace fluidbed::app
