// fluidbed run: one scene to its end, summary.json and timeseries.csv; with options its frames,
// video, montage, VTK files and the paper's plots (README.md, "Pictures, video and ParaView
// files").
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <type_traits>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/progress.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "core/run_pool.hpp"
#include "core/threads.hpp"
#include "output/frames.hpp"
#include "output/plots.hpp"
#include "output/run_checkpoint.hpp"
#include "run/checkpoint.hpp"
#include "run/ensemble.hpp"
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

// The particles whose paths a run's plots follow: --track's ids, else those nearest the jet's
// region.
std::vector<int> tracked_ids(const std::string& track, const Simulation& sim, double width) {
  return track.empty() ? nearest_particles(sim.dem().particles(), jet_region_points(width))
                       : parse_ids(track, sim.particle_count());
}

// What a run writes beside its summary and timeseries (pictures, plots, bubbles), by the names
// of visit_output_options.
nlohmann::json output_options(RunArgs a) {
  nlohmann::json j;
  visit_output_options(a, [&](const char*, const char* key, auto& v) { j[key] = v; });
  return j;
}

void set_output_options(const nlohmann::json& j, RunArgs& a) {
  visit_output_options(a, [&](const char*, const char* key, auto& v) {
    v = j.at(key).get<std::remove_reference_t<decltype(v)>>();
  });
}

// How the run was started, as its checkpoint keeps it (run/checkpoint.hpp, options.json).
nlohmann::json run_options(const RunArgs& a, double until) {
  nlohmann::json o;
  o["format"] = 1;
  o["scene"] = std::filesystem::absolute(a.scene).lexically_normal().string();
  o["overrides"] = a.overrides;
  o["until_s"] = until;
  o["threads"] = a.threads;
  o["checkpoint_every_s"] = a.checkpoint_every;
  o["outputs"] = output_options(a);
  return o;
}

// `run --resume DIR`: the run's arguments from its checkpoint; anything given on the command line
// must say the same (or a changed run would pass for the old one).
RunArgs resumed_args(const RunArgs& a, const Checkpoint& c) {
  const std::string head = "cannot resume " + a.resume + ": ";
  if (!a.out.empty() && std::filesystem::absolute(a.out).lexically_normal() !=
                            std::filesystem::absolute(a.resume).lexically_normal())
    throw InputError(head + "--out " + a.out +
                     " is not the run's folder (a resumed run finishes in DIR)");
  RunArgs r = a;
  r.out = a.resume;
  try {
    const nlohmann::json& o = c.options;
    if (o.at("format").get<int>() != 1)
      throw InputError(head + "the checkpoint is of another format");
    if (o.contains("ensemble"))
      throw InputError(head + "it is one seed of the ensemble in " +
                       o.at("ensemble").get<std::string>() +
                       ": resume the ensemble (fluidbed run --resume " +
                       o.at("ensemble").get<std::string>() + ")");
    if (r.scene.empty()) r.scene = o.at("scene").get<std::string>();
    if (r.overrides.empty()) r.overrides = o.at("overrides").get<std::vector<std::string>>();
    const double until = o.at("until_s").get<double>();
    if (a.until >= 0.0 && a.until != until) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "--until %.9g differs from the run's %.9g", a.until, until);
      throw InputError(head + msg);
    }
    r.until = until;
    if (!a.threads_given) r.threads = o.at("threads").get<int>();
    if (a.checkpoint_every < 0.0) r.checkpoint_every = o.at("checkpoint_every_s").get<double>();
    // The pictures, plots and bubbles are the run's: one given again must be the same.
    const nlohmann::json& outputs = o.at("outputs");
    const nlohmann::json given = output_options(a);
    for (const std::string& key : a.outputs_given)
      if (const nlohmann::json& value = given.at(key); outputs.at(key) != value)
          throw InputError(head + "its output option " + key + " was " + outputs.at(key).dump() +
                           ", not " + value.dump() + " (leave the output options out to resume)");
    set_output_options(outputs, r);
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + c.folder + "/options.json is not a checkpoint's options");
  }
  return r;
}

// How `run --seeds` was started, kept in DIR/ensemble.json for `run --resume DIR`.
nlohmann::json ensemble_identity(const RunArgs& a) {
  nlohmann::json o = run_options(a, a.until);
  o["kind"] = "run --seeds";
  o["seeds"] = a.seeds;
  return o;
}

bool is_run_ensemble(const std::string& dir) {
  namespace fs = std::filesystem;
  return fs::is_regular_file(fs::path(dir) / "ensemble.json") && !has_checkpoint(dir);
}

// `run --resume DIR` of an ensemble: its arguments from DIR/ensemble.json; only --threads (which
// changes no result) may be given beside it.
RunArgs resumed_ensemble_args(const RunArgs& given) {
  const std::string head = "cannot resume " + given.resume + ": ";
  if (!given.scene.empty() || !given.overrides.empty() || given.until >= 0.0 ||
      !given.seeds.empty() || !given.outputs_given.empty() || given.checkpoint_every >= 0.0)
    throw InputError(head + "a resumed ensemble takes its scene and options from "
                            "DIR/ensemble.json (give only --resume DIR and, if wanted, --threads)");
  check_resume_out(given.out, given.resume, head, "ensemble");
  const std::string path = (std::filesystem::path(given.resume) / "ensemble.json").string();
  RunArgs r = given;
  r.out = given.resume;
  try {
    std::ifstream in = open_input_file(path, "ensemble file");
    const nlohmann::json o = nlohmann::json::parse(in);
    if (o.at("format").get<int>() != 1 || o.at("kind").get<std::string>() != "run --seeds")
      throw InputError(head + path + " is not a run ensemble's");
    r.scene = o.at("scene").get<std::string>();
    r.overrides = o.at("overrides").get<std::vector<std::string>>();
    r.until = o.at("until_s").get<double>();
    if (!given.threads_given) r.threads = o.at("threads").get<int>();
    r.checkpoint_every = o.at("checkpoint_every_s").get<double>();
    r.seeds = o.at("seeds").get<std::string>();
    set_output_options(o.at("outputs"), r);
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + path + " is not a run ensemble's");
  }
  return r;
}

// A member that finished before the ensemble stopped: its summary.json, and its dp against time
// from its timeseries.csv (the first two columns, t and dp) for the ensemble's dp chart.
bool finished_member(const std::string& dir, nlohmann::json& summary, SeedTrace& trace) {
  namespace fs = std::filesystem;
  const fs::path d(dir);
  if (has_checkpoint(dir) || !fs::is_regular_file(d / "summary.json")) return false;
  try {
    std::ifstream in(d / "summary.json");
    summary = nlohmann::json::parse(in);
  } catch (const std::exception&) {
    return false;  // unreadable: the member runs again
  }
  std::ifstream csv(d / "timeseries.csv");
  std::string line;
  std::getline(csv, line);  // header
  while (std::getline(csv, line)) {
    char* end = nullptr;
    const double t = std::strtod(line.c_str(), &end);
    if (*end != ',') break;
    trace.t.push_back(t);
    trace.dp.push_back(std::strtod(end + 1, nullptr));
  }
  return true;
}

// `run --seeds`: the scene from each packing, side by side (one run a core), each member's usual
// files under DIR/seeds/S/, the ensemble's summary.json in DIR (run/ensemble.hpp) and, with
// --plots, DIR/dp.png with every seed's dp. Each member keeps its checkpoint as `run` does
// (DIR/seeds/S/checkpoint/), and DIR/ensemble.json says how the ensemble was started: an
// interrupt stops every member (status 130, no ensemble summary) and `run --resume DIR` reads the
// finished members back, resumes the stopped ones and starts those not begun. The first member
// that fails fails the ensemble (status 3) once the others ended.
int run_ensemble(const RunArgs& a) {
  const bool resume = !a.resume.empty();
  if (a.output.frames || a.output.video || a.output.vtk || !a.output.montage.empty())
    throw InputError(
        "--seeds cannot be combined with --frames, --video, --vtk or --montage (pictures are of "
        "one run: without --seeds, of the scene's own packing; of another seed's, with --set "
        "particles.seed=S where the scene packs its own bed)");
  if (a.scene.empty()) throw InputError("run: give a scene file (fluidbed run SCENE.toml)");
  Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  s.threads = a.threads;
  check_seeded_start(s);
  const std::vector<std::uint64_t> seeds = parse_seeds(a.seeds, lattice_seed(s));
  const std::string out = a.out.empty() ? default_out(a.scene) : a.out;
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw InputError("cannot create output folder " + out + ": " + ec.message());
  fs::remove(fs::path(out) / "summary.json", ec);  // only a finished ensemble has one
  auto member_dir = [&](std::uint64_t seed) {
    return (fs::path(out) / "seeds" / std::to_string(seed)).string();
  };
  if (!resume) {
    // A new ensemble: no member may resume from, or be read back as, an older one's run.
    for (const std::uint64_t seed : seeds) {
      remove_run_checkpoint(member_dir(seed));
      fs::remove(fs::path(member_dir(seed)) / "summary.json", ec);
    }
    write_file_atomically((fs::path(out) / "ensemble.json").string(),
                          [&](std::ostream& o) { o << ensemble_identity(a).dump(2) << "\n"; });
  }
  {
    std::ofstream scene_out(fs::path(out) / "scene.toml");
    scene_out << "# the scene as run, every value resolved (each seed's: seeds/S/scene.toml)\n"
              << to_toml(s);
  }
  std::vector<nlohmann::json> summaries(seeds.size());
  std::vector<SeedTrace> traces(seeds.size());
  std::vector<int> completed(seeds.size(), 0);
  std::mutex print_mutex;
  auto say = [&](const std::string& line) {
    std::lock_guard lock(print_mutex);
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  const InterruptGuard interrupts;
  auto member = [&](std::size_t k) {
    const std::uint64_t seed = seeds[k];
    const std::string dir = member_dir(seed);
    traces[k].seed = seed;
    if (resume && finished_member(dir, summaries[k], traces[k])) {
      completed[k] = 1;
      say("seed " + std::to_string(seed) + ": finished before, read back from " + dir + "/");
      return;
    }
    traces[k] = SeedTrace{seed, {}, {}};
    if (InterruptGuard::received() != 0) return;  // not begun: a resume starts it
    Settings sk = with_seed(s, seed);
    const std::string scene_toml = to_toml(sk);
    std::optional<Checkpoint> checkpoint;
    if (resume && has_checkpoint(dir)) {
      checkpoint = read_checkpoint(dir);
      if (checkpoint->scene_toml != scene_toml)
        throw InputError("cannot resume seed " + std::to_string(seed) + " in " + dir +
                         ": its scene is not the ensemble's (" +
                         first_difference(scene_toml, checkpoint->scene_toml) + ")");
    }
    prepare_packed_bed(sk);
    Simulation sim(sk);
    if (checkpoint) restore_simulation(*checkpoint, sim);
    std::unique_ptr<TrajectoryRecorder> tracks;
    if (a.plots) {
      tracks = std::make_unique<TrajectoryRecorder>(tracked_ids(a.track, sim, sk.domain.width),
                                                    sk.diagnostics.output_interval, sk.time.dt);
      if (checkpoint) restore_tracks(checkpoint->folder, *tracks, sim.particle_count());
    }
    LiveRunFolder live(dir, sk.scene.name, a.bubbles, 1.0,
                       checkpoint ? checkpoint->timeseries_csv : std::string());
    {
      std::ofstream scene_out(fs::path(dir) / "scene.toml");
      // A packed start from particles.packing_scene packs with that scene's own seed unless an
      // ensemble sets it, which no scene key says: the comment does, and how to run it again.
      scene_out << "# the scene as run, every value resolved; an ensemble's member: its particles "
                   "start from lattice seed "
                << seed << " (packed: the packing scene's bed packed from that seed), which this "
                << "file alone does not set; run it again with --seeds " << seed
                << ",T (any other seed T)\n"
                << scene_toml;
    }
    RunOptions opt;
    opt.until = a.until >= 0.0 ? a.until : sk.time.end;
    opt.bubbles = a.bubbles;
    if (tracks) opt.on_step = [&](const Simulation& x) { tracks->observe(x); };
    opt.on_row = [&](const TimeseriesRow& row) { live.row(row); };
    opt.stop = [] { return InterruptGuard::received() != 0; };
    // The member's checkpoint, as `run`'s: periodic and at an interrupt; its options name the
    // ensemble, which alone resumes it.
    nlohmann::json options = run_options(a, opt.until);
    options["ensemble"] = out;
    options["seed"] = seed;
    checkpoint_with_outputs(opt, {dir, scene_toml, options, a.bubbles, nullptr, tracks.get()},
                            checkpoint ? &*checkpoint : nullptr);
    set_checkpoint_interval(opt, a.checkpoint_every);
    if (checkpoint) {
      char line[160];
      std::snprintf(line, sizeof line, "seed %llu: resumed at t = %.6g s",
                    static_cast<unsigned long long>(seed), sim.time());
      say(line);
    }
    RunResult r;
    try {
      r = run_simulation(sim, opt);
    } catch (const SimulationFailure& e) {
      live.failed(e.what());
      throw SimulationFailure("seed " + std::to_string(seed) + ": " + e.what());
    }
    if (!r.completed) {
      live.interrupted(sim.time(), std::string("stopped by ") +
                                       InterruptGuard::name(InterruptGuard::received()));
      return;
    }
    write_run_outputs(dir, r);
    live.completed(sim.time());
    remove_run_checkpoint(dir);
    if (!sk.diagnostics.save_state.empty())
      sim.save_state((fs::path(dir) / sk.diagnostics.save_state).string());
    if (tracks)
      plot_run(dir, r, tracks->tracks(), sk.domain.width, sk.domain.height, sim.has_gas());
    for (const auto& row : r.rows) {
      traces[k].t.push_back(row.t);
      traces[k].dp.push_back(row.dp);
    }
    summaries[k] = r.summary;
    completed[k] = 1;
    char line[200];
    std::snprintf(line, sizeof line, "seed %llu: t = %.4g s in %.3g s wall; wrote %s/",
                  static_cast<unsigned long long>(seed), sim.time(),
                  r.summary["wall_time_s"].get<double>(), dir.c_str());
    say(line);
  };
  // One run a core, each on a.threads threads (0: one per core, so the seeds one after another).
  const int cores = resolve_threads(0), per_run = resolve_threads(a.threads);
  std::printf("%s: %zu seeds, %d side by side\n", s.scene.name.c_str(), seeds.size(),
              std::max(1, cores / per_run));
  std::fflush(stdout);
  std::vector<std::function<void()>> tasks;
  for (std::size_t k = 0; k < seeds.size(); ++k) tasks.push_back([&, k] { member(k); });
  RunPool(std::max(1, cores / per_run)).run(tasks);
  if (InterruptGuard::received() != 0 ||
      std::find(completed.begin(), completed.end(), 0) != completed.end()) {
    std::fprintf(stderr,
                 "interrupted: each seed's timeseries so far is in %s/seeds/S/, no ensemble "
                 "summary.json; resume with: fluidbed run --resume %s\n",
                 out.c_str(), out.c_str());
    return 130;
  }
  nlohmann::json summary = ensemble_summary(summaries, seeds);
  write_file_atomically((fs::path(out) / "summary.json").string(),
                        [&](std::ostream& o) { o << summary.dump(2) << "\n"; });
  const nlohmann::json& e = summary["ensemble"];
  for (const char* key :
       {"dp_mean_pa", "dp_spectrum.dominant_frequency_refined_hz", "bed_height_mean_m",
        "bed_height_m", "solid_fraction", "bubbles.formed_per_s", "bubbles.mean_d_eq_m"})
    if (e.contains(key)) std::printf("  %s: %s\n", key, ensemble_line(e[key]).c_str());
  if (a.plots && s.gas.enabled) {
    const std::string p = (fs::path(out) / "dp.png").string();
    plot_dp_ensemble(p, traces, summary.value("bed_weight_per_area_pa", 0.0), s.scene.name);
    std::printf("wrote %s\n", p.c_str());
  }
  std::printf("wrote %s/summary.json (the ensemble of %zu seeds) and %s/seeds/S/\n", out.c_str(),
              seeds.size(), out.c_str());
  return 0;
}

}  // namespace

int run_command(const RunArgs& given) {
  if (!given.resume.empty() && is_run_ensemble(given.resume))
    return run_ensemble(resumed_ensemble_args(given));
  if (!given.seeds.empty()) {
    if (!given.resume.empty())
      throw InputError("cannot resume " + given.resume +
                       ": it holds no ensemble (DIR/ensemble.json); a resumed ensemble takes its "
                       "seeds from there (give only --resume DIR)");
    return run_ensemble(given);
  }
  std::optional<Checkpoint> checkpoint;
  RunArgs a = given;
  if (!given.resume.empty()) {
    checkpoint = read_checkpoint(given.resume);
    a = resumed_args(given, *checkpoint);
  } else if (given.scene.empty()) {
    throw InputError("run: give a scene file (fluidbed run SCENE.toml) or --resume DIR");
  }
  Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  s.threads = a.threads;
  const std::string scene_toml = to_toml(s);
  if (checkpoint && scene_toml != checkpoint->scene_toml)
    throw InputError("cannot resume " + given.resume +
                     ": the scene is not the one the run started with (" +
                     first_difference(scene_toml, checkpoint->scene_toml) + ")");
  const std::string out = a.out.empty() ? default_out(a.scene) : a.out;
  prepare_packed_bed(s);
  Simulation sim(s);
  if (checkpoint) restore_simulation(*checkpoint, sim);
  std::unique_ptr<TrajectoryRecorder> tracks;
  if (a.plots) {
    tracks = std::make_unique<TrajectoryRecorder>(tracked_ids(a.track, sim, s.domain.width),
                                                  s.diagnostics.output_interval, s.time.dt);
  }
  const double until = a.until >= 0.0 ? a.until : s.time.end;
  // Frames, video, montage, VTK: snapshots at exact times, drawn and written by a worker thread.
  std::unique_ptr<FrameOutput> pictures;
  if (const FrameOptions fo = frame_options(a.output, asset_dir()); fo.any()) {
    pictures = std::make_unique<FrameOutput>(out, fo, sim, until,
                                             checkpoint ? checkpoint->folder : std::string());
    if (!checkpoint) pictures->observe(sim);  // the starting state, when it is an output time
  }
  if (tracks && checkpoint) restore_tracks(checkpoint->folder, *tracks, sim.particle_count());
  RunOptions opt;
  if (pictures || tracks)
    opt.on_step = [&](const Simulation& x) {
      if (pictures) pictures->observe(x);
      if (tracks) tracks->observe(x);
    };
  opt.bubbles = a.bubbles;
  // The folder says what the run is doing while it runs (run/live_folder.hpp), and an
  // interrupt (SIGINT, SIGTERM) stops it at the end of a step.
  LiveRunFolder live(out, s.scene.name, a.bubbles, 1.0,
                     checkpoint ? checkpoint->timeseries_csv : std::string());
  {
    std::ofstream scene_out(std::filesystem::path(out) / "scene.toml");
    scene_out << "# the scene as run, every value resolved\n" << scene_toml;
  }
  // Checkpoints (run/checkpoint.hpp): periodic and at an interrupt, with the pictures' and the
  // trajectories' state beside the run's.
  checkpoint_with_outputs(
      opt, {out, scene_toml, run_options(a, until), a.bubbles, pictures.get(), tracks.get()},
      checkpoint ? &*checkpoint : nullptr);
  set_checkpoint_interval(opt, a.checkpoint_every);
  opt.on_row = [&](const TimeseriesRow& row) { live.row(row); };
  opt.stop = [] { return InterruptGuard::received() != 0; };
  const InterruptGuard interrupts;
  RunResult r;
  try {
    r = run_with_progress(sim, until, std::move(opt));
  } catch (const SimulationFailure& e) {
    live.failed(e.what());
    throw;
  }
  if (!r.completed) {
    const std::string why =
        std::string("stopped by ") + InterruptGuard::name(InterruptGuard::received());
    live.interrupted(sim.time(), why);
    std::fprintf(stderr, "interrupted at t = %.6g s; resume with: fluidbed run --resume %s\n",
                 sim.time(), out.c_str());
    return 130;
  }
  const FrameStats picture_stats = pictures ? pictures->finish() : FrameStats{};
  write_run_outputs(out, r);
  live.completed(sim.time());
  remove_run_checkpoint(out);  // the finished run's folder holds what an unstopped run's does
  if (!s.diagnostics.save_state.empty())
    sim.save_state((std::filesystem::path(out) / s.diagnostics.save_state).string());
  std::printf(
      "%s: %lld steps of %zu particles to t = %.4g s in %.3g s wall (%.3g particle-steps/s)\n",
      s.scene.name.c_str(), static_cast<long long>(r.summary["steps"].get<std::int64_t>()),
      sim.particle_count(), sim.time(), r.summary["wall_time_s"].get<double>(),
      r.summary["particle_steps_per_s"].get<double>());
  std::printf("wrote %s/summary.json and %s/timeseries.csv\n", out.c_str(), out.c_str());
  if (r.bubbles) {
    const auto& b = r.summary["bubbles"];
    auto num = [&](const char* k) { return b[k].is_number() ? b[k].get<double>() : 0.0; };
    std::printf(
        "bubbles: %.2f formed per s, %.2f eruptions per s, mean D_e %.1f mm, rise %.3f m/s, "
        "regime %s; wrote %s/bubbles.csv and %s/mixing.csv\n",
        num("formed_per_s"), num("eruptions_per_s"), 1e3 * num("mean_d_eq_m"),
        num("mean_rise_velocity_m_s"), b["regime"].get<std::string>().c_str(), out.c_str(),
        out.c_str());
  }
  if (pictures)
    report_frame_output(out, a.output, picture_stats, r.summary["wall_time_s"].get<double>());
  if (tracks) {
    const auto files =
        plot_run(out, r, tracks->tracks(), s.domain.width, s.domain.height, sim.has_gas());
    for (const auto& f : files) std::printf("wrote %s\n", f.c_str());
  }
  return 0;
}

}  // namespace fluidbed::app
