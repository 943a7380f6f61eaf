// fluidbed reproduce: every figure and number of the paper that the model gives, in one folder
// with a report to hold next to the paper (Xu & Yu 1997).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "core/atomic_file.hpp"
#include "core/run_pool.hpp"
#include "core/threads.hpp"
#include "output/frames.hpp"
#include "output/plots.hpp"
#include "output/run_checkpoint.hpp"
#include "run/checkpoint.hpp"
#include "run/ensemble.hpp"
#include "run/packed_bed.hpp"
#include "run/run.hpp"
#include "run/sweep.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "sim/simulation.hpp"
#include "studies/study.hpp"

namespace fluidbed::app {
namespace {

namespace fs = std::filesystem;

struct TrackedRun {
  RunResult result;
  std::vector<Trajectory> tracks;
  double wall = 0.0;
};

// An interrupt (SIGINT, SIGTERM) stopped a run or a sweep of the report.
struct Interrupted {};

// A run of the report that finished leaves this beside its files (its wall time); `--resume`
// reads such a run back instead of running it again.
constexpr const char* kRunDone = "reproduce-run.json";
// Whether `reproduce --resume` is finishing a report (set once, before any run).
bool resuming = false;

std::optional<TrackedRun> finished_run(const fs::path& dir) {
  if (!resuming) return std::nullopt;
  std::ifstream done(dir / kRunDone), summary(dir / "summary.json");
  if (!done || !summary) return std::nullopt;
  try {
    TrackedRun r;
    r.wall = nlohmann::json::parse(done).at("wall_s").get<double>();
    r.result.summary = nlohmann::json::parse(summary);
    return r;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // run it again
  }
}

// A run of the report keeps a checkpoint in DIR/checkpoint/ (run/checkpoint.hpp: every 60 wall
// seconds once it is expected to take over 2 minutes, and at an interrupt) with its trajectories
// and montage; `reproduce --resume` continues it from there to the same bits.
TrackedRun run_tracked(Settings s, double until,
                       const std::vector<std::pair<double, double>>& track_at,
                       const fs::path& dir, const std::vector<double>& montage) {
  TrackedRun out;
  prepare_packed_bed(s);
  const std::string scene_toml = to_toml(s);
  const nlohmann::json options = {{"format", 1}, {"reproduce_run", dir.filename().string()},
                                  {"until_s", until}, {"montage", montage}};
  std::optional<Checkpoint> checkpoint;
  if (resuming && has_checkpoint(dir.string())) {
    checkpoint = read_checkpoint(dir.string());
    if (checkpoint->scene_toml != scene_toml || checkpoint->options != options)
      throw InputError("cannot resume " + dir.string() +
                       ": its checkpoint is of another run (the scene or the end time differ)");
  } else {
    remove_checkpoint(dir.string());  // of an earlier report in this folder
  }
  Simulation sim(s);
  if (checkpoint) restore_simulation(*checkpoint, sim);
  TrajectoryRecorder recorder(nearest_particles(sim.dem().particles(), track_at), 0.005, s.time.dt);
  if (checkpoint) restore_tracks(checkpoint->folder, recorder, sim.particle_count());
  std::unique_ptr<FrameOutput> pictures;  // DIR/montage.png at the given times
  if (!montage.empty()) {
    FrameOptions fo;
    fo.montage = montage;
    fo.font = asset_dir() + "/fonts/DejaVuSans.ttf";
    pictures = std::make_unique<FrameOutput>(dir.string(), fo, sim, until,
                                             checkpoint ? checkpoint->folder : std::string());
    if (!checkpoint) pictures->observe(sim);
  }
  RunOptions opt;
  opt.until = until;
  opt.bubbles = true;  // bubbles.csv, mixing.csv and their figures beside every run
  opt.stop = [] { return InterruptGuard::received() != 0; };
  opt.on_step = [&](const Simulation& m) {
    recorder.observe(m);
    if (pictures) pictures->observe(m);
  };
  checkpoint_with_outputs(opt, {dir.string(), scene_toml, options, true, pictures.get(), &recorder},
                          checkpoint ? &*checkpoint : nullptr);
  set_checkpoint_interval(opt, -1.0);  // the default: reproduce has no --checkpoint-every
  const auto start = std::chrono::steady_clock::now();
  out.result = run_simulation(sim, opt);
  if (!out.result.completed) throw Interrupted{};
  if (pictures) pictures->finish();
  remove_run_checkpoint(dir.string());
  out.wall = opt.wall_before +
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.tracks = recorder.tracks();
  return out;
}

// One number into its printf format; "n/a" for a value the run could not measure (no bubble
// tracked, no spectrum).
// One scene of the report: run with the bubble analysis (tracking particles near `track_at`),
// its files and figures into `dir`.
TrackedRun run_into(const fs::path& dir, const Settings& s, double until,
                    const std::vector<std::pair<double, double>>& track_at = {},
                    const std::vector<double>& montage = {}) {
  if (std::optional<TrackedRun> done = finished_run(dir)) return *done;
  if (InterruptGuard::received() != 0) throw Interrupted{};  // stopped: start no other run
  fs::create_directories(dir);
  TrackedRun r = run_tracked(s, until, track_at, dir, montage);
  write_run_outputs(dir.string(), r.result);
  plot_run(dir.string(), r.result, r.tracks, s.domain.width, s.domain.height, true);
  write_file_atomically((dir / kRunDone).string(), [&](std::ostream& o) {
    o << nlohmann::json{{"wall_s", r.wall}}.dump() << "\n";
  });
  return r;
}

std::string fmt(const char* f, double v) {
  if (!std::isfinite(v)) return "n/a";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

double num(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

double num(const nlohmann::json& j, const char* object, const char* key) {
  return j.contains(object) ? num(j[object], key) : NAN;
}

std::string text(const nlohmann::json& j, const char* object, const char* key) {
  return j.contains(object) && j[object].contains(key) && j[object][key].is_string()
             ? j[object][key].get<std::string>()
             : "n/a";
}

// The report's bubble rows of one run (the bubble analysis of model.md section 6).
void bubble_rows(std::ostringstream& md, const char* run, const nlohmann::json& j) {
  const double d = num(j, "bubbles", "mean_d_eq_m");
  const double rise = num(j, "bubbles", "mean_rise_velocity_m_s");
  const double ref = num(j, "bubbles", "mean_rise_velocity_2d_ref_m_s");
  const double erupt = num(j, "bubbles", "eruptions_per_s");
  const double f = num(j, "dp_spectrum", "dominant_frequency_hz");
  md << "| " << run << ": regime (Figs 9-11: bubbling, then slugging) | slugging | "
     << text(j, "bubbles", "regime") << fmt(" (slug in %.0f %% of frames", 100.0 * num(j, "bubbles", "slugging_fraction"))
     << fmt(", jet reaching the surface in %.0f %%)", 100.0 * num(j, "bubbles", "spouting_fraction"))
     << " | |\n";
  md << "| " << run << ": bubbles formed, eruptions at the surface | | "
     << fmt("%.2f formed per s, ", num(j, "bubbles", "formed_per_s"))
     << fmt("%.2f eruptions per s", erupt) << " | |\n";
  md << "| " << run << ": eruptions against the dominant frequency of dp (Welch) | equal for one "
     << "bubble per cycle | " << fmt("%.2f per s against ", erupt) << fmt("%.2f Hz", f) << " | "
     << fmt("%+.0f %%", 100.0 * (erupt / f - 1.0)) << " |\n";
  md << "| " << run << ": mean rise velocity against 0.5 sqrt(g D_e) (2D, Pyle and Harrison) "
     << "| reference, not a fit | " << fmt("%.3f m/s", rise) << fmt(" at D_e %.1f mm", 1e3 * d)
     << fmt(" (reference %.3f m/s)", ref) << " | " << fmt("%+.0f %%", 100.0 * (rise / ref - 1.0))
     << " |\n";
}

// A run's dp cycle in words: the verdict of analysis/cycles.hpp with the peak it judged.
std::string cycle_words(const nlohmann::json& j) {
  std::string w = j.contains("dp_cycle") && j["dp_cycle"].is_string() ? j["dp_cycle"].get<std::string>() : "n/a";
  if (j.contains("dp_dominant_period_s") && j["dp_dominant_period_s"].is_number())
    w += fmt(": period %.3f s", num(j, "dp_dominant_period_s")) +
         fmt(", cycle-length spread %.0f %%", 100.0 * num(j, "dp_cycle_length_cv"));
  w += fmt("; dp %.0f Pa", num(j, "dp_mean_pa")) + fmt(" +- %.0f Pa", num(j, "dp_std_pa"));
  return w;
}

// The energy budget of a run in one sentence: what the gas put in and where it went.
std::string energy_words(const nlohmann::json& j) {
  if (!j.contains("energy")) return "no energy budget";
  const auto& e = j["energy"];
  const double gas = e.value("gas_work_j", NAN), res = e.value("residual_j", NAN);
  const double lost = e.value("dashpot_dissipation_j", NAN) + e.value("friction_dissipation_j", NAN);
  const double t = num(j, "sim_time_s");
  return fmt("the gas did %.3g J of work on the particles", gas) + fmt(" in %.1f s", t) +
         fmt(", the dashpots and friction took %.3g J", lost) +
         fmt(", the mechanical energy changed by %+.3g J", e.value("mechanical_change_j", NAN)) +
         fmt(", and %+.3g J is unaccounted for", res) + fmt(" (the integration's residual: %+.0f %% of the gas's work", 100.0 * res / gas) +
         fmt(", %+.3g W)", e.value("residual_per_s_w", NAN));
}

// The ideal case as measured, beside the paper's description and the literature.
void ideal_section(std::ostringstream& md, const nlohmann::json& ij, const nlohmann::json& gj,
                   const nlohmann::json& pj) {
  md << "## The ideal case (Figs 16-17) as measured\n\n";
  md << "The paper: \"a bubble ... generated at the jet region grows to convert to a slug, and "
     << "particles scatter over the upper part of the bed ... a bubble experiences its generation, "
     << "growth and burst-out before a new bubble is formed, and this cycle is quite stable\" "
     << "(dp swinging on a scale of 10^4 Pa).\n\n";
  auto describe = [&](const char* name, const nlohmann::json& j) {
    md << "- **" << name << "**: regime " << text(j, "bubbles", "regime")
       << fmt(" (slug in %.0f %% of the frames", 100.0 * num(j, "bubbles", "slugging_fraction"))
       << fmt(", %.2f bubbles formed per s", num(j, "bubbles", "formed_per_s"))
       << fmt(", %.2f eruptions per s)", num(j, "bubbles", "eruptions_per_s")) << "; dp "
       << cycle_words(j) << fmt(" (std / mean %.3f)", num(j, "dp_std_pa") / num(j, "dp_mean_pa"))
       << "; energy: " << energy_words(j) << ".\n";
  };
  describe("ideal case, the paper's scheme (incremental displacement)", ij);
  describe("ideal case, geometric overlap", gj);
  describe("realistic bed (eta = 0.15, gamma = 0.3)", pj);
  md << "\nMontages: ![ideal](ideal/montage.png) ![ideal, geometric](ideal_geometric/montage.png)\n\n";
  md << "Hard-sphere simulations with perfectly elastic, frictionless collisions have been reported "
     << "to fluidize homogeneously, without bubbles (Hoomans et al., Chem. Eng. Sci. 51 (1996) 99): "
     << "bubbles need collisions that lose energy, so that particles cluster. An ideal bed here has "
     << "no contact losses at all; what it loses is the drag on particle fluctuations (inside the "
     << "gas's net work) and the integration's residual. Where that residual is a sizeable share of "
     << "the gas's work, the scheme itself is the bed's damping, and its behaviour follows the "
     << "numerics rather than the model; compare the two contact forms above, whose residuals "
     << "differ in sign and size (the energy study gives both for an elastic box).\n\n";
}

// One figure over the seeds (run/ensemble.hpp's entry), or the single run's value.
struct Figure {
  double mean = NAN, sd = NAN;  // sd: NaN with one seed
  std::size_t n = 0;
};

Figure figure(const std::vector<nlohmann::json>& summaries, const char* key) {
  const nlohmann::json e = ensemble_statistics(summaries);
  Figure f;
  if (!e.contains(key)) return f;
  f.mean = e[key]["mean"].get<double>();
  f.sd = e[key]["std"].is_number() ? e[key]["std"].get<double>() : NAN;
  f.n = e[key]["n"].get<std::size_t>();
  return f;
}

// "1.78 +- 0.12 m/s (3 seeds)", or the one seed's value "1.78 m/s (1 seed)".
std::string pm(const Figure& f, const char* format, const char* unit, double scale = 1.0) {
  if (f.n == 0) return "n/a";
  std::string s = fmt(format, scale * f.mean);
  if (f.n > 1) s += " +- " + fmt(format, scale * f.sd);
  return s + unit + " (" + std::to_string(f.n) + (f.n == 1 ? " seed)" : " seeds)");
}

// Whether the paper's value lies within two standard deviations of the ensemble mean.
std::string within_two_sd(const Figure& f, double paper) {
  if (f.n < 2 || !std::isfinite(f.sd)) return "one seed: spread not measured";
  return std::abs(f.mean - paper) <= 2.0 * f.sd ? "the paper's value within 2 std"
                                                : "the paper's value outside 2 std";
}

// A scene from every seed, side by side: the first seed's run in `base` (with its figures, as
// without an ensemble), the others in base/seeds/S/; with more than one seed, base/ensemble.json
// (run/ensemble.hpp) over all of them. Returns the runs in seed order.
std::vector<TrackedRun> run_seeds(const fs::path& base, const Settings& s, double until,
                                  const std::vector<std::uint64_t>& seeds,
                                  const std::vector<std::pair<double, double>>& track_at = {}) {
  const int workers = std::max(1, resolve_threads(0) / resolve_threads(s.threads));
  const std::vector<TrackedRun> runs =
      RunPool(workers).map<TrackedRun>(seeds.size(), [&](std::size_t k) {
        const fs::path dir = k == 0 ? base : base / "seeds" / std::to_string(seeds[k]);
        return run_into(dir, with_seed(s, seeds[k]), until, track_at);
      });
  if (seeds.size() > 1) {
    std::vector<nlohmann::json> summaries;
    for (const auto& r : runs) summaries.push_back(r.result.summary);
    write_file_atomically((base / "ensemble.json").string(), [&](std::ostream& o) {
      o << ensemble_summary(summaries, seeds).dump(2) << "\n";
    });
  }
  return runs;
}

std::vector<nlohmann::json> summaries_of(const std::vector<TrackedRun>& runs) {
  std::vector<nlohmann::json> s;
  for (const auto& r : runs) s.push_back(r.result.summary);
  return s;
}

// The scenes the report's runs start from, resolved (the sweep checks its own).
nlohmann::json report_scenes(const ReproduceArgs& a) {
  const std::string scenes = asset_dir() + "/scenes/";
  nlohmann::json j;
  for (const char* name : {"xu_yu_1997.toml", "ideal.toml"})
    j[name] = to_toml(load_scene(scenes + name, a.overrides));
  return j;
}

// How the report was started (DIR/reproduce.json), for `reproduce --resume DIR`.
nlohmann::json reproduce_json(const ReproduceArgs& a) {
  return {{"format", 1},      {"quick", a.quick},     {"seeds", a.seeds},
          {"overrides", a.overrides}, {"threads", a.threads}, {"scenes", report_scenes(a)}};
}

// `reproduce --resume DIR`: the arguments from DIR/reproduce.json (only --threads beside it).
ReproduceArgs resumed_reproduce_args(const ReproduceArgs& given) {
  const std::string head = "cannot resume " + given.resume + ": ";
  if (given.options_given)
    throw InputError(head + "a resumed report takes --quick, --seeds and --set from "
                            "DIR/reproduce.json (give only --resume DIR and, if wanted, --threads)");
  check_resume_out(given.out, given.resume, head, "report");
  if (!fs::is_directory(given.resume)) throw InputError(head + "not a folder");
  std::ifstream in(fs::path(given.resume) / "reproduce.json");
  if (!in) throw InputError(head + "no report to resume there (no reproduce.json)");
  ReproduceArgs a = given;
  a.out = given.resume;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("format").get<int>() != 1) throw InputError(head + "reproduce.json of another format");
    a.quick = j.at("quick").get<bool>();
    a.seeds = j.at("seeds").get<std::string>();
    a.overrides = j.at("overrides").get<std::vector<std::string>>();
    if (!given.threads_given) a.threads = j.at("threads").get<int>();
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
// report's finished runs and studies goes.
void forget_finished_parts(const fs::path& out) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (auto it = fs::recursive_directory_iterator(out, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name == kRunDone || (name == "report.json" && it->path().parent_path().parent_path().filename() == "studies"))
      stale.push_back(it->path());
  }
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
  // An interrupt stops the runs, the sweeps and the studies at the end of a step (the sweeps
  // with their checkpoints, the studies with their finished points kept).
  const InterruptGuard interrupts;
  const std::string scenes = asset_dir() + "/scenes/";
  auto log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  // Lengths: the full report, or a quick pass that shows every figure at lower fidelity.
  const double paper_time = a.quick ? 1.5 : 6.0;
  const double ideal_time = a.quick ? 1.5 : 6.0;
  const double uniform_time = a.quick ? 1.0 : 3.0;
  SweepOptions so;
  so.run_time = a.quick ? 0.5 : 1.5;
  so.averaging_start = a.quick ? 0.2 : 0.5;
  if (a.quick) so.velocities = {0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  so.threads = 2;
  so.out_dir = (fs::path(out) / "sweep").string();
  so.log = log;
  so.resume = resuming;
  so.stop = [] { return InterruptGuard::received() != 0; };
  so.command = reproduce_json(a);
  const double averaging = a.quick ? 0.5 : 1.0;

  // Every scene refused before the first step, not after the runs before it.
  for (const char* name : {"xu_yu_1997.toml", "ideal.toml"})
    refuse_unsafe_scene(load_scene(scenes + name, a.overrides));
  // The packings: 3 by default (1 with --quick); the paper's bed, its uniform twin and the sweep
  // run from each, the ideal case from the first.
  const std::vector<std::uint64_t> seeds =
      parse_seeds(a.seeds.empty() ? (a.quick ? "1" : "3") : a.seeds,
                  lattice_seed(load_scene(scenes + "xu_yu_1997.toml", a.overrides)));
  // 1. The paper's bed at 2.8 m/s (Figs 8, 12-13, 15), tracking particles from the jet region.
  log("== the paper's bed at U = 2.8 m/s");
  Settings paper = load_scene(scenes + "xu_yu_1997.toml", a.overrides);
  paper.threads = a.threads;
  paper.diagnostics.averaging_start = averaging;
  const std::vector<TrackedRun> prs = run_seeds(fs::path(out) / "paper_bed", paper, paper_time,
                                                seeds, jet_region_points(paper.domain.width));
  const TrackedRun& pr = prs.front();

  // 1b. The same bed fed over its whole bottom (a uniform distributor): the like-with-like check of
  // dp against the bed weight (model.md 2.1: the jetted bed's dead zones rest on the floor).
  log("== the paper's bed at U = 2.8 m/s through a uniform distributor");
  Settings uniform = load_scene(scenes + "xu_yu_1997.toml", a.overrides);
  uniform.threads = a.threads;
  uniform.inlet.kind = InletKind::Uniform;
  uniform.diagnostics.averaging_start = averaging;
  const std::vector<TrackedRun> urs =
      run_seeds(fs::path(out) / "uniform", uniform, uniform_time, seeds);
  const TrackedRun& ur = urs.front();

  // 2. The ideal case (Figs 16-17).
  log("== the ideal case (eta = 0, gamma = 0)");
  Settings ideal = with_seed(load_scene(scenes + "ideal.toml", a.overrides), seeds.front());
  ideal.threads = a.threads;
  ideal.diagnostics.averaging_start = averaging;
  // Six pictures over the run, to hold beside the paper's description of Figs 16-17.
  std::vector<double> ideal_montage;
  for (int k = 1; k <= 6; ++k) ideal_montage.push_back(ideal_time * k / 6.0);
  const TrackedRun ir = run_into(fs::path(out) / "ideal", ideal, ideal_time, {}, ideal_montage);
  // The same with the geometric overlap: the contact form that conserves energy best in the
  // elastic box (study energy), so that the scheme's own loss is not what keeps the bed calm.
  Settings ideal_geo = ideal;
  ideal_geo.contact.displacement = Displacement::Geometric;
  const TrackedRun ig =
      run_into(fs::path(out) / "ideal_geometric", ideal_geo, ideal_time, {}, ideal_montage);

  // 3. The velocity sweep (Fig. 6) and U_mf.
  log("== the velocity sweep");
  Settings sweep_scene = load_scene(scenes + "xu_yu_1997.toml", a.overrides);
  std::vector<SweepResult> srs;
  std::vector<nlohmann::json> sweep_summaries;
  for (std::size_t k = 0; k < seeds.size(); ++k) {  // one sweep after another, runs side by side
    SweepOptions o = so;
    if (k > 0) o.out_dir = (fs::path(so.out_dir) / "seeds" / std::to_string(seeds[k])).string();
    fs::create_directories(o.out_dir);
    srs.push_back(run_sweep(with_seed(sweep_scene, seeds[k]), o));
    if (srs.back().interrupted) throw Interrupted{};
    write_sweep_outputs(srs.back(), o, sweep_scene.scene.name);
    sweep_summaries.push_back(sweep_summary(srs.back(), o, sweep_scene.scene.name));
  }
  const SweepResult& sr = srs.front();
  const Figure umf = figure(sweep_summaries, "umf_m_s");
  if (seeds.size() > 1) {
    const nlohmann::json ens = ensemble_summary(sweep_summaries, seeds);
    write_file_atomically((fs::path(so.out_dir) / "ensemble.json").string(),
                          [&](std::ostream& o) { o << ens.dump(2) << "\n"; });
    plot_sweep_ensemble(
        (fs::path(so.out_dir) / "sweep_ensemble.png").string(), srs,
        ens["ensemble"].contains("umf_m_s") ? ens["ensemble"]["umf_m_s"] : nlohmann::json(nullptr),
        sweep_scene.scene.name);
  }

  // 4. The studies (speed against accuracy, stability, model choices): tiny with --quick. They
  // use their own scenes; the --set overrides above do not apply to them.
  if (InterruptGuard::received() != 0) throw Interrupted{};
  std::vector<study::Report> studies;
  for (const study::Info& info : study::all_studies()) {
    study::Options so_study;
    so_study.out = (fs::path(out) / "studies" / info.name).string();
    so_study.size = a.quick ? study::Size::Tiny : study::Size::Full;
    so_study.log = log;
    if (resuming)
      if (std::optional<study::Report> done = study::finished_study(so_study.out, so_study.size)) {
        log("== study " + std::string(info.name) + ": finished before, kept");
        studies.push_back(*done);
        continue;
      }
    log("== study " + std::string(info.name));
    // Resumed: a study stopped midway keeps the points it finished.
    so_study.resume = resuming && fs::exists(fs::path(so_study.out) / "study.json");
    so_study.stop = [] { return InterruptGuard::received() != 0; };
    so_study.command = "fluidbed reproduce --out " + out;
    try {
      studies.push_back(study::run_study(info, so_study));
    } catch (const study::Interrupted&) {
      throw Interrupted{};
    }
  }

  // 5. The report.
  const auto& pj = pr.result.summary;
  const auto& ij = ir.result.summary;
  const double weight = num(pj, "bed_weight_per_area_pa");
  const double dp_mean = num(pj, "dp_mean_pa");
  const double wall_per_sim = pr.wall / std::max(paper_time, 1e-9);
  std::ostringstream md;
  md << "# fluidbed against Xu & Yu (1997)\n\n";
  md << "Made by `fluidbed reproduce" << (a.quick ? " --quick" : "")
     << (a.seeds.empty() ? "" : " --seeds " + a.seeds) << "`. Every number below "
     << "is measured by this run; none is tuned to the paper.\n\n";
  md << "A fluidized bed is chaotic: another packing of the same particles gives another run. "
     << "The paper's bed, its uniform twin and the sweep ran from " << seeds.size()
     << (seeds.size() == 1 ? " packing (lattice seed " : " packings (lattice seeds ");
  for (std::size_t k = 0; k < seeds.size(); ++k) md << (k ? ", " : "") << seeds[k];
  md << (a.quick && a.seeds.empty() ? "; `--quick` runs one, so no spread is measured" : "")
     << "). Figures marked +- are the mean and sample standard deviation over the seeds (n - 1), "
     << "with their number; the other rows, the figures and the ideal case are the first seed's "
     << "run (the other seeds' runs are in `paper_bed/seeds/S/`, `uniform/seeds/S/` and "
     << "`sweep/seeds/S/`, their spread in each folder's `ensemble.json`).\n\n";
  md << "| paper figure or number | paper | fluidbed | difference |\n|---|---|---|---|\n";
  if (umf.n > 0) {
    md << "| U_mf, decreasing branch (Fig. 6, point E) | 1.8 m/s (Wen-Yu 1.77) | "
       << pm(umf, "%.2f", " m/s") << " | " << fmt("%+.0f %%", 100.0 * (umf.mean / 1.8 - 1.0))
       << "; " << within_two_sd(umf, 1.8) << " |\n";
  } else {
    md << "| U_mf, decreasing branch (Fig. 6) | 1.8 m/s | not found: " << sr.umf.why << " | |\n";
  }
  md << "| plateau of the decreasing branch / bed weight per area | about 1 | "
     << fmt("%.0f Pa / ", sr.umf.plateau) << fmt("%.0f Pa", sr.bed_weight_per_area) << " | "
     << fmt("%+.0f %%", 100.0 * (sr.umf.plateau / sr.bed_weight_per_area - 1.0)) << " |\n";
  const auto& uj = ur.result.summary;
  const Figure dp_u = figure(summaries_of(urs), "dp_mean_pa");
  const Figure dp_j = figure(summaries_of(prs), "dp_mean_pa");
  md << "| mean dp at 2.8 m/s, uniform distributor (model A: the bed carries its weight) | "
     << "1.005 of W/A (measured, model.md 2.1) | " << pm(dp_u, "%.0f", " Pa")
     << fmt(" (weight %.0f Pa)", weight) << " | "
     << fmt("%+.0f %%", 100.0 * (dp_u.mean / weight - 1.0)) << " |\n";
  md << "| mean dp at 2.8 m/s, central jet (eq 30, Fig. 8; dead zones rest on the floor) | "
     << "below W/A (DPMFoam 0.77) | " << pm(dp_j, "%.0f", " Pa")
     << fmt(" = %.3f of W/A", dp_j.mean / weight) << " | "
     << fmt("%.3f of the uniform bed's", dp_j.mean / dp_u.mean) << " |\n";
  md << "| dominant frequency of dp at 2.8 m/s, central jet (Welch) | | "
     << pm(figure(summaries_of(prs), "dp_spectrum.dominant_frequency_refined_hz"), "%.2f", " Hz")
     << " | |\n";
  md << "| mean bed height after start-up, central jet | | "
     << pm(figure(summaries_of(prs), "bed_height_mean_m"), "%.3f", " m") << " | |\n";
  md << "| start-up peak of dp (Fig. 8) | far above the stable level | "
     << fmt("%.0f Pa", num(pj, "dp_max_pa")) << fmt(" at t = %.3f s", num(pj, "dp_max_time_s"))
     << " | " << fmt("%.1f x the mean", num(pj, "dp_max_pa") / dp_mean) << " |\n";
  const Figure overlap = figure(summaries_of(prs), "max_overlap_ratio");
  md << "| max overlap ratio at start-up (Fig. 15) | 1.7 % | " << pm(overlap, "%.2f", " %", 100.0)
     << " | " << within_two_sd(overlap, 0.017) << " |\n";
  md << "| max overlap ratio after start-up (Fig. 15) | well below 1 % | "
     << fmt("%.2f %%", 100.0 * num(pj, "max_overlap_ratio_after_startup")) << " | |\n";
  md << "| ideal case: a regular dp cycle (Fig. 17) | one bubble forms, grows to a slug and "
     << "bursts before the next: quite stable | " << cycle_words(ij) << " | |\n";
  md << "| ideal case, geometric overlap: a regular dp cycle | (as above) | " << cycle_words(ig.result.summary)
     << " | |\n";
  md << "| realistic bed: dp cycle | irregular | " << cycle_words(pj) << " | |\n";
  bubble_rows(md, "jetted bed", pj);
  bubble_rows(md, "uniform distributor", uj);
  bubble_rows(md, "ideal case", ij);
  bubble_rows(md, "ideal case, geometric overlap", ig.result.summary);
  md << "| cost of 1 s of the paper's bed | 9 h CPU (HP-735) | "
     << fmt("%.0f s wall", wall_per_sim)
     << " (" << resolve_threads(paper.threads) << (resolve_threads(paper.threads) == 1 ? " thread)" : " threads)")
     << " | "
     << fmt("%.0f x faster", 9.0 * 3600.0 / wall_per_sim) << " |\n\n";
  md << "## Figures\n\n";
  md << "Fig. 6, the sweep: ![sweep](sweep/sweep.png)\n\n";
  if (seeds.size() > 1)
    md << "The sweeps of every packing, each faint, their mean bold, U_mf's mean +- one standard "
       << "deviation: ![sweeps](sweep/sweep_ensemble.png)\n\n";
  md << "Fig. 8, dp against time at 2.8 m/s: ![dp](paper_bed/dp.png)\n\n";
  md << "Fig. 15, max overlap ratio: ![overlap](paper_bed/overlap.png)\n\n";
  md << "Figs 12-13, particles from the jet region: ![trajectory](paper_bed/trajectory.png)\n\n";
  md << "Fig. 17, the ideal case's dp: ![ideal](ideal/dp.png)\n\n";
  md << "Bubbles of the jetted bed (size against height, rise velocity against size with "
     << "0.5 sqrt(g D_e)): ![bubbles](paper_bed/bubbles.png)\n\n";
  md << "Its dp spectrum (Welch): ![spectrum](paper_bed/dp_spectrum.png); the Lacey mixing "
     << "index of the two halves by initial height: ![mixing](paper_bed/mixing.png)\n\n";
  md << "The same bed through a uniform distributor: ![uniform dp](uniform/dp.png) "
     << "![uniform bubbles](uniform/bubbles.png)\n\n";
  md << "The ideal case's bubbles: ![ideal bubbles](ideal/bubbles.png)\n\n";
  ideal_section(md, ij, ig.result.summary, pj);
  md << "## Studies: speed against accuracy, stability, model choices\n\n";
  md << "Each study below is `fluidbed study NAME" << (a.quick ? " --size tiny" : "")
     << "`; its table is `studies/NAME/study.csv`, its full findings `studies/NAME/summary.md`. "
     << "The advice is derived from the study's own measurements by the rule it states.\n\n";
  for (const auto& st : studies) {
    md << "### " << st.title << "\n\n";
    for (const auto& c : st.charts)
      md << "![" << st.name << "](studies/" << st.name << "/" << c << ")\n\n";
    md << st.advice << " (" << st.points << " points, " << st.failed << " failed runs recorded; "
       << fmt("%.0f s", st.wall_time) << "; [findings](studies/" << st.name << "/summary.md))\n\n";
  }
  md << "## Settings\n\n";
  md << "- paper bed: `assets/scenes/xu_yu_1997.toml`, " << paper_time << " s simulated, "
     << "averaging from " << averaging << " s; the same with `inlet.kind = uniform`, "
     << uniform_time << " s; ideal: `assets/scenes/ideal.toml`, " << ideal_time
     << " s, and the same with `contact.displacement = geometric`.\n";
  md << "- bubbles: the scene's `[bubbles]` settings (threshold, interval, minimum diameter); the "
     << "regime rule and the eruption count are in the README (Bubbles and slugs).\n";
  md << "- sweep: " << sr.up.size() << " velocities, " << so.run_time << " s each, averaging from "
     << so.averaging_start << " s; U_mf: least-squares line through the defluidized points of "
     << "the decreasing branch meets the mean of its plateau (split at least squared error).\n";
  const double total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.overrides.empty()) {
    md << "- overrides applied to every scene:";
    for (const auto& o : a.overrides) md << " `" << o << "`";
    md << "\n";
  }
  md << "- wall time of this report: " << fmt("%.0f s", total) << ".\n";
  const std::string report = (fs::path(out) / "report.md").string();
  write_file_atomically(report, [&](std::ostream& o) { o << md.str(); });
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
