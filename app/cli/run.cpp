// fluidbed run: one scene to its end, summary.json and timeseries.csv; with options its frames,
// video, montage, VTK files and the paper's plots (docs/pictures.md).
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
#include "core/json_fields.hpp"
#include "core/run_pool.hpp"
#include "core/threads.hpp"
#include "output/frames.hpp"
#include "output/plots.hpp"
#include "output/run_outputs.hpp"
#include "run/checkpoint.hpp"
#include "run/ensemble.hpp"
#include "run/run_folder.hpp"
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
  return track.empty() ? nearest_particles(sim.dem(), jet_region_points(width))
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
nlohmann::json run_options(RunArgs a, double until) {
  a.scene = std::filesystem::absolute(a.scene).lexically_normal().string();
  a.until = until;
  nlohmann::json o = {{"format", 1}};
  o.update(fields_json(a, [](auto& r, auto&& f) { run_identity_fields(r, f); }));
  o["outputs"] = output_options(a);
  return o;
}

// Reads `o`'s fields into `r`, but for those the command line gave anew: --threads (which changes
// no result) and --checkpoint-every.
void take_run_options(const nlohmann::json& o, const RunArgs& given, RunArgs& r) {
  fields_from_json(o, r, [](auto& x, auto&& f) { run_identity_fields(x, f); });
  if (given.threads_given) r.threads = given.threads;
  if (given.checkpoint_every >= 0.0) r.checkpoint_every = given.checkpoint_every;
  set_output_options(o.at("outputs"), r);
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
    const double until = o.at("until_s").get<double>();
    if (a.until >= 0.0 && a.until != until) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "--until %.9g differs from the run's %.9g", a.until, until);
      throw InputError(head + msg);
    }
    // The pictures, plots and bubbles are the run's: one given again must be the same.
    const nlohmann::json& outputs = o.at("outputs");
    const nlohmann::json given = output_options(a);
    for (const std::string& key : a.outputs_given)
      if (const nlohmann::json& value = given.at(key); outputs.at(key) != value)
        throw InputError(head + "its output option " + key + " was " + outputs.at(key).dump() +
                         ", not " + value.dump() + " (leave the output options out to resume)");
    take_run_options(o, a, r);
    // A scene or --set lines given again are checked against the run's (run/run_folder.hpp).
    if (!a.scene.empty()) r.scene = a.scene;
    if (!a.overrides.empty()) r.overrides = a.overrides;
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + c.folder + "/options.json is not a checkpoint's options");
  }
  return r;
}

// The job of one run of `run` (alone, or one seed of an ensemble) into `dir`: the scene, the
// end time, the bubble analysis and the figures (--plots) it asks for; the pictures are the
// caller's.
RunJob run_job(const RunArgs& a, Settings s, const std::string& scene_note) {
  RunJob job;
  job.until = a.until >= 0.0 ? a.until : s.time.end;
  job.bubbles = a.bubbles;
  job.started = run_options(a, job.until);
  job.scene_note = scene_note;
  if (a.plots) {
    const std::string track = a.track;
    const double width = s.domain.width;
    job.outputs.push_back(std::make_unique<PlotOutput>(
        [track, width](const Simulation& sim) { return tracked_ids(track, sim, width); },
        s.diagnostics.output_interval));
  }
  job.scene = std::move(s);
  return job;
}

// What a run is told to stop by: an interrupt (SIGINT, SIGTERM), named in its status.json.
RunControl interruptible(bool resume, double checkpoint_every) {
  RunControl c;
  c.resume = resume;
  c.checkpoint_every = checkpoint_every;
  c.stop = [] { return InterruptGuard::received() != 0; };
  c.stop_reason = [] {
    return std::string("stopped by ") + InterruptGuard::name(InterruptGuard::received());
  };
  return c;
}

// `run --resume DIR` of an ensemble: its arguments from DIR/ensemble.json; only --threads (which
// changes no result) may be given beside it.
RunArgs resumed_ensemble_args(const RunArgs& given) {
  const std::string head = "cannot resume " + given.resume + ": ";
  check_resume_only(!given.scene.empty() || !given.overrides.empty() || given.until >= 0.0 ||
                        !given.seeds.empty() || !given.outputs_given.empty() ||
                        given.checkpoint_every >= 0.0,
                    given.out, given.resume, "ensemble", "its scene and options from DIR/ensemble.json");
  const nlohmann::json o = read_ensemble_identity(given.resume, "run --seeds", head);
  RunArgs r = given;
  r.out = given.resume;
  try {
    take_run_options(o, given, r);
    r.seeds = o.at("seeds_option").get<std::string>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + given.resume + "/ensemble.json is not a run ensemble's");
  }
  return r;
}

// A member's dp against time, from its timeseries.csv (the first two columns, t and dp), for
// the ensemble's dp chart.
SeedTrace dp_trace(const std::string& dir, std::uint64_t seed) {
  SeedTrace trace{seed, {}, {}};
  std::ifstream csv(std::filesystem::path(dir) / "timeseries.csv");
  std::string line;
  std::getline(csv, line);  // header
  while (std::getline(csv, line)) {
    char* end = nullptr;
    const double t = std::strtod(line.c_str(), &end);
    if (*end != ',') break;
    trace.t.push_back(t);
    trace.dp.push_back(std::strtod(end + 1, nullptr));
  }
  return trace;
}

// `run --seeds`: the scene from each packing, side by side (one run a core), each member's usual
// files under DIR/seeds/S/, the ensemble's summary.json in DIR (run/ensemble.hpp) and, with
// --plots, DIR/dp.png with every seed's dp. Each member keeps its checkpoint as `run` does
// (DIR/seeds/S/checkpoint/), and DIR/ensemble.json says how the ensemble was started: an
// interrupt stops every member (status 130, no ensemble summary) and `run --resume DIR` reads the
// finished members back, resumes the stopped ones and starts those not begun. The first member
// that fails fails the ensemble (status 3) once the others ended.
int run_seeds(const RunArgs& a) {
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
  {
    std::ofstream scene_out(fs::path(out) / "scene.toml");
    scene_out << "# the scene as run, every value resolved (each seed's: seeds/S/scene.toml)\n"
              << to_toml(s);
  }
  std::mutex print_mutex;
  auto say = [&](const std::string& line) {
    std::lock_guard lock(print_mutex);
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  const InterruptGuard interrupts;
  EnsembleJob job;
  job.dir = out;
  job.seeds = seeds;
  job.identity = run_options(a, a.until);
  job.identity["kind"] = "run --seeds";
  job.identity["seeds_option"] = a.seeds;
  std::vector<SeedTrace> traces(seeds.size());
  job.member = [&](std::size_t k, std::uint64_t seed,
                   const std::string& dir) -> std::optional<nlohmann::json> {
    const std::string tag = "seed " + std::to_string(seed) + ": ";
    if (InterruptGuard::received() != 0 && !(resume && run_ended(dir)))
      return std::nullopt;  // not begun: a resume starts it
    // A packed start from particles.packing_scene packs with that scene's own seed unless an
    // ensemble sets it, which no scene key says: the comment does, and how to run it again.
    const std::string note =
        "# the scene as run, every value resolved; an ensemble's member: its particles start "
        "from lattice seed " + std::to_string(seed) +
        " (packed: the packing scene's bed packed from that seed), which this file alone does "
        "not set; run it again with --seeds " + std::to_string(seed) + ",T (any other seed T)\n";
    RunJob member = run_job(a, with_seed(s, seed), note);
    // Its checkpoint's options name the ensemble, which alone resumes it.
    member.started["ensemble"] = out;
    member.started["seed"] = seed;
    RunControl control = interruptible(resume, a.checkpoint_every);
    control.log = [&](const std::string& line) { say(tag + line); };
    const RunEnd end = run_in_folder(dir, member, control);
    if (end.how == RunEnd::How::failed) throw SimulationFailure(tag + end.error);
    if (end.how == RunEnd::How::stopped) return std::nullopt;
    traces[k] = dp_trace(dir, seed);
    if (end.read_back) {
      say(tag + "finished before, read back from " + dir + "/");
    } else {
      char line[200];
      std::snprintf(line, sizeof line, "t = %.4g s in %.3g s wall; wrote %s/", end.t,
                    end.result.summary["wall_time_s"].get<double>(), dir.c_str());
      say(tag + line);
    }
    return end.result.summary;
  };
  // One run a core, each on a.threads threads (0: one per core, so the seeds one after another).
  const int cores = resolve_threads(0), per_run = resolve_threads(a.threads);
  job.side_by_side = std::max(1, cores / per_run);
  std::printf("%s: %zu seeds, %d side by side\n", s.scene.name.c_str(), seeds.size(),
              job.side_by_side);
  std::fflush(stdout);
  const EnsembleResult r = run_ensemble(job, resume);
  if (InterruptGuard::received() != 0 || !r.complete) {
    std::fprintf(stderr,
                 "interrupted: each seed's timeseries so far is in %s/seeds/S/, no ensemble "
                 "summary.json; resume with: fluidbed run --resume %s\n",
                 out.c_str(), out.c_str());
    return 130;
  }
  const nlohmann::json& e = r.summary["ensemble"];
  for (const char* key :
       {"dp_mean_pa", "dp_spectrum.dominant_frequency_refined_hz", "bed_height_mean_m",
        "bed_height_m", "solid_fraction", "bubbles.formed_per_s", "bubbles.mean_d_eq_m"})
    if (e.contains(key)) std::printf("  %s: %s\n", key, ensemble_line(e[key]).c_str());
  if (a.plots && s.gas.enabled) {
    const std::string p = (fs::path(out) / "dp.png").string();
    plot_dp_ensemble(p, traces, r.summary.value("bed_weight_per_area_pa", 0.0), s.scene.name);
    std::printf("wrote %s\n", p.c_str());
  }
  std::printf("wrote %s/summary.json (the ensemble of %zu seeds) and %s/seeds/S/\n", out.c_str(),
              seeds.size(), out.c_str());
  return 0;
}

}  // namespace

int run_command(const RunArgs& given) {
  if (!given.resume.empty() && holds_ensemble(given.resume) && !has_checkpoint(given.resume))
    return run_seeds(resumed_ensemble_args(given));
  if (!given.seeds.empty()) {
    if (!given.resume.empty())
      throw InputError("cannot resume " + given.resume +
                       ": it holds no ensemble (DIR/ensemble.json); a resumed ensemble takes its "
                       "seeds from there (give only --resume DIR)");
    return run_seeds(given);
  }
  RunArgs a = given;
  if (!given.resume.empty()) {
    a = resumed_args(given, read_checkpoint(given.resume));
  } else if (given.scene.empty()) {
    throw InputError("run: give a scene file (fluidbed run SCENE.toml) or --resume DIR");
  }
  Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  s.threads = a.threads;
  const std::string out = a.out.empty() ? default_out(a.scene) : a.out;
  RunJob job = run_job(a, s, "# the scene as run, every value resolved\n");
  // Frames, video, montage, VTK: snapshots at exact times, drawn and written by a worker thread.
  PictureOutput* pictures = nullptr;
  if (const FrameOptions fo = frame_options(a.output, asset_dir(), s); fo.any()) {
    job.outputs.push_back(std::make_unique<PictureOutput>(out, fo));
    pictures = static_cast<PictureOutput*>(job.outputs.back().get());
  }
  const PlotOutput* plots = a.plots ? static_cast<PlotOutput*>(job.outputs.front().get()) : nullptr;
  RunControl control = interruptible(!given.resume.empty(), a.checkpoint_every);
  control.progress = progress_printer(job.until);
  const InterruptGuard interrupts;
  const RunEnd end = run_in_folder(out, job, control);
  end_progress(control.progress);
  if (end.how == RunEnd::How::failed) throw SimulationFailure(end.error);
  if (end.how == RunEnd::How::stopped) {
    std::fprintf(stderr, "interrupted at t = %.6g s; resume with: fluidbed run --resume %s\n",
                 end.t, out.c_str());
    return 130;
  }
  const nlohmann::json& summary = end.result.summary;
  std::printf(
      "%s: %lld steps of %lld particles to t = %.4g s in %.3g s wall (%.3g particle-steps/s)\n",
      s.scene.name.c_str(), static_cast<long long>(summary["steps"].get<std::int64_t>()),
      static_cast<long long>(summary["particles"].get<std::int64_t>()), end.t,
      summary["wall_time_s"].get<double>(), summary["particle_steps_per_s"].get<double>());
  std::printf("wrote %s/summary.json and %s/timeseries.csv\n", out.c_str(), out.c_str());
  if (a.bubbles) {
    const auto& b = summary["bubbles"];
    auto num = [&](const char* k) { return b[k].is_number() ? b[k].get<double>() : 0.0; };
    std::printf(
        "bubbles: %.2f formed per s, %.2f eruptions per s, mean D_e %.1f mm, rise %.3f m/s, "
        "regime %s; wrote %s/bubbles.csv and %s/mixing.csv\n",
        num("formed_per_s"), num("eruptions_per_s"), 1e3 * num("mean_d_eq_m"),
        num("mean_rise_velocity_m_s"), b["regime"].get<std::string>().c_str(), out.c_str(),
        out.c_str());
  }
  if (pictures)
    report_frame_output(out, a.output, pictures->stats(), summary["wall_time_s"].get<double>());
  if (plots)
    for (const auto& f : plots->files()) std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace fluidbed::app
