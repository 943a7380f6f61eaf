// fluidbed reproduce: every figure and number of the paper that the model gives, in one folder
// with a report to hold next to the paper (Xu & Yu 1997). This file runs the report's parts;
// cli/paper_report.cpp writes report.md from what they measured.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/paper_report.hpp"
#include "core/atomic_file.hpp"
#include "core/json_fields.hpp"
#include "core/threads.hpp"
#include "output/plots.hpp"
#include "output/run_outputs.hpp"
#include "output/sweep_outputs.hpp"
#include "run/ensemble.hpp"
#include "run/run_folder.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "studies/common.hpp"

namespace fluidbed::app {
namespace {

namespace fs = std::filesystem;

// An interrupt (SIGINT, SIGTERM) stopped a run or a sweep of the report.
struct Interrupted {};

// Whether `reproduce --resume` is finishing a report (set once, before any run).
bool resuming = false;

// One scene of the report, a run in a folder (run/run_folder.hpp) with the bubble analysis,
// particles tracked from near `track_at` with the run's figures, and a montage at the given
// times. It keeps a checkpoint (every 60 wall seconds once it is expected to take over 2
// minutes, and at an interrupt); `reproduce --resume` reads a finished run back and continues a
// stopped one to the same bits. A failure fails the report.
RunEnd run_into(const fs::path& dir, const Settings& s, double until,
                const std::vector<std::pair<double, double>>& track_at = {},
                const std::vector<double>& montage = {}) {
  if (InterruptGuard::received() != 0 && !(resuming && run_ended(dir.string())))
    throw Interrupted{};  // stopped: start no other run
  RunJob job;
  job.scene = s;
  job.until = until;
  job.bubbles = true;  // bubbles.csv, mixing.csv and their figures beside every run
  job.started = {{"format", 1}, {"reproduce_run", dir.filename().string()}, {"until_s", until},
                 {"montage", montage}};
  job.outputs.push_back(std::make_unique<PlotOutput>(
      [track_at](const Simulation& sim) { return nearest_particles(sim.dem(), track_at); },
      0.005));
  if (!montage.empty()) {
    FrameOptions fo;
    fo.montage = montage;
    fo.look.gas_arrow_reference = gas_arrow_reference(s);
    fo.font = asset_dir() + "/fonts/DejaVuSans.ttf";
    job.outputs.push_back(std::make_unique<PictureOutput>(dir.string(), fo));
  }
  RunControl control;
  control.resume = resuming;
  control.stop = [] { return InterruptGuard::received() != 0; };
  control.stop_reason = [] {
    return std::string("stopped by ") + InterruptGuard::name(InterruptGuard::received());
  };
  RunEnd end = run_in_folder(dir.string(), job, control);
  if (end.how == RunEnd::How::failed) throw SimulationFailure(dir.string() + ": " + end.error);
  if (end.how == RunEnd::How::stopped) throw Interrupted{};
  return end;
}

// A scene from every seed, side by side, as an ensemble (run/ensemble.hpp): each seed's run in
// base/seeds/S/, base/ensemble.json, and base/summary.json over all of them. Returns the runs in
// seed order; `first_wall` gets the first seed's wall time; each run draws a montage at the
// times `montage`.
std::vector<nlohmann::json> run_seeds(const fs::path& base, const Settings& s, double until,
                                      const std::vector<std::uint64_t>& seeds,
                                      const std::vector<std::pair<double, double>>& track_at,
                                      double* first_wall = nullptr,
                                      const std::vector<double>& montage = {}) {
  EnsembleJob job;
  job.dir = base.string();
  job.seeds = seeds;
  job.identity = {{"kind", "reproduce run"}, {"until_s", until}};
  job.side_by_side = std::max(1, resolve_threads(0) / resolve_threads(s.threads));
  job.member = [&](std::size_t k, std::uint64_t seed,
                   const std::string& dir) -> std::optional<nlohmann::json> {
    const RunEnd end = run_into(dir, with_seed(s, seed), until, track_at, montage);
    if (k == 0 && first_wall) *first_wall = end.wall;
    return end.result.summary;
  };
  const EnsembleResult r = run_ensemble(job, resuming);
  if (!r.complete) throw Interrupted{};
  return r.summaries;
}

// The second bed of the full report (not --quick), run as shipped: the --set overrides are the
// paper bed's.
constexpr const char* kSecondBed = "van_wachem_2001.toml";

// The scenes the report's runs start from, resolved (the sweep checks its own).
nlohmann::json report_scenes(const ReproduceArgs& a) {
  const std::string scenes = asset_dir() + "/scenes/";
  nlohmann::json j;
  for (const char* name : {"xu_yu_1997.toml", "ideal.toml"})
    j[name] = to_toml(load_scene(scenes + name, a.overrides));
  if (!a.quick) j[kSecondBed] = to_toml(load_scene(scenes + kSecondBed));  // as shipped
  return j;
}

// How the report was started (DIR/reproduce.json), for `reproduce --resume DIR`.
nlohmann::json reproduce_json(ReproduceArgs a) {
  nlohmann::json j = {{"format", 1}};
  j.update(fields_json(a, [](auto& r, auto&& f) { reproduce_identity_fields(r, f); }));
  j["scenes"] = report_scenes(a);
  return j;
}

// `reproduce --resume DIR`: the arguments from DIR/reproduce.json (only --threads beside it).
ReproduceArgs resumed_reproduce_args(const ReproduceArgs& given) {
  const std::string head = "cannot resume " + given.resume + ": ";
  check_resume_only(given.options_given, given.out, given.resume, "report",
                    "--quick, --seeds and --set from DIR/reproduce.json");
  if (!fs::is_directory(given.resume)) throw InputError(head + "not a folder");
  std::ifstream in(fs::path(given.resume) / "reproduce.json");
  if (!in) throw InputError(head + "no report to resume there (no reproduce.json)");
  ReproduceArgs a = given;
  a.out = given.resume;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("format").get<int>() != 1) throw InputError(head + "reproduce.json of another format");
    fields_from_json(j, a, [](auto& r, auto&& f) { reproduce_identity_fields(r, f); });
    if (given.threads_given) a.threads = given.threads;
    // The finished runs are kept only if the scenes are still the ones they ran.
    const nlohmann::json now = report_scenes(a);
    for (const auto& [name, toml] : j.at("scenes").items()) {
      const std::string change =
          first_difference(now.value(name, std::string()), toml.get<std::string>());
      if (!change.empty())
        throw InputError(head + "scene " + name + " is not the one the report started with (" +
                         change + ")");
    }
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + "its reproduce.json does not say how the report was started");
  }
  return a;
}

// A new report in a folder that held another: what a later --resume could mistake for this
// report's finished runs and studies (their finished markers) goes.
void forget_finished_parts(const fs::path& out) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (auto it = fs::recursive_directory_iterator(out, ec); !ec && it != fs::end(it);
       it.increment(ec))
    if (it->path().filename() == "status.json") stale.push_back(it->path());
  for (const auto& p : stale) fs::remove(p, ec);
}

int reproduce_report(const ReproduceArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string out = a.out.empty() ? "out/reproduce" : a.out;
  fs::create_directories(out);
  resuming = !a.resume.empty();
  if (!resuming) {
    forget_finished_parts(out);
    write_file_atomically((fs::path(out) / "reproduce.json").string(),
                          [&](std::ostream& o) { o << reproduce_json(a).dump(2) << "\n"; });
  }
  fs::remove(fs::path(out) / "report.md");  // only a finished report is there
  // An interrupt stops the runs, the sweeps and the studies at the end of a step (with their
  // checkpoints; the studies with their finished points kept).
  const InterruptGuard interrupts;
  const std::string scenes = asset_dir() + "/scenes/";
  auto log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  PaperRuns r;
  // Lengths: the full report, or a quick pass that shows every figure at lower fidelity.
  r.paper_time = a.quick ? 1.5 : 6.0;
  r.ideal_time = a.quick ? 1.5 : 6.0;
  r.uniform_time = a.quick ? 1.0 : 3.0;
  r.averaging = a.quick ? 0.5 : 1.0;
  SweepOptions so;
  so.run_time = a.quick ? 0.5 : 1.5;
  so.averaging_start = a.quick ? 0.2 : 0.5;
  if (a.quick) so.velocities = {0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  so.threads = 2;
  so.out_dir = (fs::path(out) / "sweep").string();
  so.resume = resuming;
  so.stop = [] { return InterruptGuard::received() != 0; };
  so.command = reproduce_json(a);
  r.sweep_run_time = so.run_time;
  r.sweep_averaging_start = so.averaging_start;

  // Every scene refused before the first step, not after the runs before it.
  for (const char* name : {"xu_yu_1997.toml", "ideal.toml"})
    refuse_unsafe_scene(load_scene(scenes + name, a.overrides));
  if (!a.quick) refuse_unsafe_scene(load_scene(scenes + kSecondBed));
  // The packings: 3 by default (1 with --quick); the paper's bed, its uniform twin and the sweep
  // run from each, the ideal case from the first.
  r.seeds = parse_seeds(a.seeds.empty() ? (a.quick ? "1" : "3") : a.seeds,
                        lattice_seed(load_scene(scenes + "xu_yu_1997.toml", a.overrides)));
  // 1. The paper's bed at 2.8 m/s (Figs 8, 12-13, 15), tracking particles from the jet region.
  log("== the paper's bed at U = 2.8 m/s");
  Settings paper = load_scene(scenes + "xu_yu_1997.toml", a.overrides);
  paper.threads = a.threads;
  paper.diagnostics.averaging_start = r.averaging;
  r.paper_threads = paper.threads;
  r.paper = run_seeds(fs::path(out) / "paper_bed", paper, r.paper_time, r.seeds,
                      jet_region_points(paper.domain.width), &r.paper_wall);

  // 1b. The same bed fed over its whole bottom (a uniform distributor): the like-with-like check of
  // dp against the bed weight (model.md 2.1: the jetted bed's dead zones rest on the floor).
  log("== the paper's bed at U = 2.8 m/s through a uniform distributor");
  Settings uniform = load_scene(scenes + "xu_yu_1997.toml", a.overrides);
  uniform.threads = a.threads;
  uniform.inlet.kind = InletKind::Uniform;
  uniform.diagnostics.averaging_start = r.averaging;
  r.uniform = run_seeds(fs::path(out) / "uniform", uniform, r.uniform_time, r.seeds, {});

  // 2. The ideal case (Figs 16-17).
  log("== the ideal case (eta = 0, gamma = 0)");
  Settings ideal = with_seed(load_scene(scenes + "ideal.toml", a.overrides), r.seeds.front());
  ideal.threads = a.threads;
  ideal.diagnostics.averaging_start = r.averaging;
  // Six pictures over the run, to hold beside the paper's description of Figs 16-17.
  std::vector<double> ideal_montage;
  for (int k = 1; k <= 6; ++k) ideal_montage.push_back(r.ideal_time * k / 6.0);
  r.ideal = run_into(fs::path(out) / "ideal", ideal, r.ideal_time, {}, ideal_montage).result.summary;
  // The same with the geometric overlap: the contact form that conserves energy best in the
  // elastic box (study energy), so that the scheme's own loss is not what keeps the bed calm.
  Settings ideal_geo = ideal;
  ideal_geo.contact.displacement = Displacement::Geometric;
  r.ideal_geometric =
      run_into(fs::path(out) / "ideal_geometric", ideal_geo, r.ideal_time, {}, ideal_montage)
          .result.summary;

  // 3. The velocity sweep (Fig. 6) and U_mf: one sweep per packing (output/sweep_outputs.hpp).
  log("== the velocity sweep");
  const Settings sweep_scene = load_scene(scenes + "xu_yu_1997.toml", a.overrides);
  SweepEnsemble sweeps = sweep_over_seeds(
      sweep_scene, r.seeds, so, {{"kind", "reproduce sweep"}},
      [&](std::uint64_t, const std::string& line) { log(line); });
  if (sweeps.interrupted) throw Interrupted{};
  r.sweeps = sweeps.summaries;
  r.first_sweep = std::move(sweeps.members.front());

  // 3b. The second bed (van Wachem et al. 2001) as its scene ships it, 12 s from 2 s, over the
  // first two packings: not with --quick (about 20 minutes a packing on two threads).
  if (!a.quick) {
    log("== the second bed: van Wachem et al. (2001)");
    Settings second = load_scene(scenes + kSecondBed);
    second.threads = a.threads;
    const std::size_t packings = std::min<std::size_t>(2, r.seeds.size());
    r.second_bed_seeds.assign(r.seeds.begin(), r.seeds.begin() + static_cast<long>(packings));
    std::vector<double> montage;
    for (int k = 1; k <= 6; ++k) montage.push_back(second.time.end * k / 6.0);
    r.second_bed = run_seeds(fs::path(out) / "second_bed", second, second.time.end,
                             r.second_bed_seeds, {}, nullptr, montage);
  }

  // 4. The studies (speed against accuracy, stability, model choices): tiny with --quick. They
  // use their own scenes; the --set overrides above do not apply to them.
  if (InterruptGuard::received() != 0) throw Interrupted{};
  for (const study::Info& info : study::all_studies()) {
    if (info.takes_scene) continue;  // a study of a scene the user names
    study::Options so_study;
    so_study.out = (fs::path(out) / "studies" / info.name).string();
    so_study.size = a.quick ? study::Size::Tiny : study::Size::Full;
    so_study.log = log;
    if (resuming)
      if (std::optional<study::Report> done = study::finished_study(so_study.out, so_study.size)) {
        log("== study " + std::string(info.name) + ": finished before, kept");
        r.studies.push_back(*done);
        continue;
      }
    log("== study " + std::string(info.name));
    // Resumed: a study stopped midway keeps the points it finished.
    so_study.resume = resuming && fs::exists(fs::path(so_study.out) / "study.json");
    so_study.stop = [] { return InterruptGuard::received() != 0; };
    so_study.command = "fluidbed reproduce --out " + out;
    try {
      r.studies.push_back(study::run_study(info, so_study));
    } catch (const study::Interrupted&) {
      throw Interrupted{};
    }
  }

  // 5. The report.
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string report = (fs::path(out) / "report.md").string();
  write_file_atomically(report, [&](std::ostream& o) { o << paper_report(a, r, total); });
  log("wrote " + report);
  return 0;
}

}  // namespace

int reproduce_command(const ReproduceArgs& given) {
  try {
    return reproduce_report(given.resume.empty() ? given : resumed_reproduce_args(given));
  } catch (const Interrupted&) {
    const std::string out = given.resume.empty() ? (given.out.empty() ? "out/reproduce" : given.out)
                                                 : given.resume;
    say_interrupted("fluidbed reproduce --resume " + out);
    return 130;
  }
}

}  // namespace fluidbed::app
