// What the studies share: the registry, the point runner, the CSV table, charts and the bed.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>
#include <type_traits>

#include "render/asset_dir.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/roots.hpp"
#include "core/threads.hpp"
#include "run/checkpoint.hpp"
#include "run/ensemble.hpp"
#include "run/run_folder.hpp"
#include "run/velocity_sweep.hpp"
#include "scene/scene_loader.hpp"
#include "sim/simulation.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace fs = std::filesystem;

const std::vector<Info>& all_studies() {
  static const std::vector<Info> list = {
      {"integrators",
       "Integrators and time step: drop test, restitution, energy of a packing at rest, cost",
       "about 4 min", "about 20 s", integrators_study},
      {"contact",
       "Contact displacement: incremental with backward projection (eqs 13-17) against the "
       "geometric overlap",
       "about 3 min", "about 15 s", contact_study},
      {"stiffness", "Stiffness: the paper's 50,000 N/m against Tsuji's 800 N/m",
       "about 3 min (2 x 0.8 s packing, 1.5 s bed)", "about 10 s", stiffness_study, true},
      {"coupling",
       "Coupling: particle steps per gas step, gas grid, SIMPLE tolerance; error against cost",
       "about 10 min (12 runs of 1.5 s of the paper's bed)", "about 20 s", coupling_study, true},
      {"modules", "What each physics module costs, and that scenes without it do not pay",
       "about 30 s", "a few s", modules_study},
      {"model-form",
       "Model form: model A (drag and -V grad p) against the paper's printed form (drag alone)",
       "about 20 min (two sweeps, 7 and 9 velocities, 1 s each)", "about 20 s", model_form_study,
       true},
      {"failures", "Failure detection: every way a study's run can fail, reported in words",
       "under a minute", "under a second", failures_study},
      {"energy",
       "Energy budget of an elastic frictionless box: the residual of each integrator and "
       "contact form at the paper's step and a tenth of it",
       "about 3 min (12 runs of 20,000 steps of 2400 spheres)", "about 10 s", energy_study},
      {"teaching",
       "Teaching scene: the cheap settings' bed against the paper-fidelity bed, within the "
       "bounds the teaching scene was chosen by",
       "about 15 min (10 runs of 6 s of the paper's bed, each then swept down through 8 "
       "velocities)",
       "about 15 s", teaching_study, true,
       teaching_bounds()},
      {"sensitivity",
       "Sensitivity of a scene (--scene, --vary): which settings move its figures beyond their "
       "spread over packings",
       "(points x seeds) runs of --until s of the scene, two at a time", "-", sensitivity_study,
       false, {}, true},
  };
  return list;
}

const Info* find_study(const std::string& name) {
  for (const Info& i : all_studies())
    if (name == i.name) return &i;
  return nullptr;
}

namespace {

const char* size_name(Size s) { return s == Size::Tiny ? "tiny" : "full"; }

nlohmann::json scene_study_json(const Options::SceneStudy& a) {
  return {{"scene", a.scene}, {"set", a.overrides}, {"vary", a.vary}, {"until", a.until},
          {"seeds", a.seeds}};
}

fs::path points_dir(const Options& o) { return fs::path(o.out) / "points"; }

// A point's name in the folder: the hash of what defines it.
std::string point_key(const nlohmann::json& what) { return hex_digest(what.dump()); }

}  // namespace

void check_study_resume(const Info& info, const Options& o) {
  if (!o.resume) return;
  const std::string head = "cannot resume " + o.out + ": ";
  if (!fs::is_directory(o.out)) throw InputError(head + "not a folder");
  std::ifstream in(fs::path(o.out) / "study.json");
  if (!in) throw InputError(head + "no study to resume there (no study.json)");
  std::string name, size;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    name = j.at("study").get<std::string>();
    size = j.at("size").get<std::string>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + "its study.json does not say which study it holds");
  }
  if (name != info.name)
    throw InputError(head + "it holds study " + name + ", not " + info.name);
  if (size != size_name(o.size))
    throw InputError(head + "it holds study " + name + " at --size " + size + ", not --size " +
                     size_name(o.size));
  if (info.takes_scene) {
    const Options::SceneStudy was = stored_scene_study(o.out);
    const Options::SceneStudy& now = o.scene_study;
    if (now.scene != was.scene)
      throw InputError(head + "it studies the scene " + was.scene + ", not " + now.scene);
    if (now.overrides != was.overrides || now.vary != was.vary || now.until != was.until ||
        now.seeds != was.seeds)
      throw InputError(head + "it was started with other --set, --vary, --until or --seeds "
                       "(leave them out to resume it as it was started)");
  }
}

Options::SceneStudy stored_scene_study(const std::string& dir) {
  const std::string head = "cannot resume " + dir + ": ";
  std::ifstream in(fs::path(dir) / "study.json");
  if (!in) throw InputError(head + "no study to resume there (no study.json)");
  try {
    const nlohmann::json j = nlohmann::json::parse(in).at("scene_study");
    Options::SceneStudy a;
    a.scene = j.at("scene").get<std::string>();
    a.overrides = j.at("set").get<std::vector<std::string>>();
    a.vary = j.at("vary").get<std::vector<std::string>>();
    a.until = j.at("until").get<double>();
    a.seeds = j.at("seeds").get<std::string>();
    return a;
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + "its study.json does not say which scene it studies");
  }
}

Report run_study(const Info& info, const Options& o) {
  if (o.out.empty()) throw InputError("study: an output folder is needed (--out)");
  check_study_resume(info, o);  // a refused resume touches nothing
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) throw InputError("cannot create output folder " + o.out + ": " + ec.message());
  if (!o.resume) {  // afresh: an earlier run's points are not this run's
    fs::remove_all(points_dir(o), ec);
    nlohmann::json j = {{"format", 1},
                              {"study", info.name},
                              {"size", size_name(o.size)},
                              {"command", o.command}};
    if (info.takes_scene) j["scene_study"] = scene_study_json(o.scene_study);
    write_text((fs::path(o.out) / "study.json").string(), j.dump(2) + "\n");
  }
  for (const char* f : {"study.csv", "summary.md", "status.json"})  // a finished study's
    fs::remove(fs::path(o.out) / f, ec);
  fs::create_directories(points_dir(o), ec);  // before the points' threads write into it
  const auto start = std::chrono::steady_clock::now();
  Options safe = o;  // the log, for the points' threads
  std::mutex log_mutex;
  if (o.log)
    safe.log = [&](const std::string& line) {
      std::lock_guard lock(log_mutex);
      o.log(line);
    };
  Report r = info.run(safe);
  r.name = info.name;
  r.title = info.title;
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::string md = "# Study `" + r.name + "`: " + r.title + "\n\n";
  md += "Made by `" +
        (info.takes_scene ? o.command
                          : "fluidbed study " + r.name + (o.size == Size::Tiny ? " --size tiny" : "")) +
        "` in " + fmt("%.0f s", r.wall_time) +
        " on " + std::to_string(resolve_threads(o.workers)) + " worker thread(s); " +
        std::to_string(r.points) + " points, " + std::to_string(r.failed) +
        " of them failed runs (recorded in study.csv with the reason). Every number is measured "
        "by this run.\n\n";
  md += r.findings + "\n";
  md += "## What to choose\n\n" + r.advice + "\n\n## Charts\n\n";
  for (const auto& c : r.charts) md += "![" + c + "](" + c + ")\n\n";
  write_text((fs::path(o.out) / "summary.md").string(), md);
  // The finished marker, last (run/run_folder.hpp's, with the report as its result).
  const nlohmann::json result = {
      {"name", r.name},         {"title", r.title},   {"charts", r.charts},
      {"findings", r.findings}, {"advice", r.advice}, {"points", r.points},
      {"failed", r.failed},     {"size", size_name(o.size)}};
  const nlohmann::json marker = {{"status", "completed"}, {"finished", true},
                                 {"wall_time_s", r.wall_time}, {"result", result}};
  write_text((fs::path(o.out) / "status.json").string(), marker.dump(2) + "\n");
  return r;
}

std::optional<Report> finished_study(const std::string& dir, Size size) {
  const std::optional<nlohmann::json> status = read_run_status(dir);
  if (!status || status->value("status", std::string()) != "completed") return std::nullopt;
  try {
    const nlohmann::json& j = status->at("result");
    if (j.at("size").get<std::string>() != size_name(size)) return std::nullopt;
    Report r;
    r.name = j.at("name").get<std::string>();
    r.title = j.at("title").get<std::string>();
    r.charts = j.at("charts").get<std::vector<std::string>>();
    r.findings = j.at("findings").get<std::string>();
    r.advice = j.at("advice").get<std::string>();
    r.points = j.at("points").get<int>();
    r.failed = j.at("failed").get<int>();
    r.wall_time = status->at("wall_time_s").get<double>();
    return r;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

// kg: 2700 kg/m3 x pi d^3 / 6, d = 4 mm.
double paper_particle_mass() {
  return 2700.0 * std::numbers::pi * 0.004 * 0.004 * 0.004 / 6.0;
}

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void stop_if_asked(const Options& o) {
  if (o.stop && o.stop()) throw Interrupted();
}

RunResult run_to_end(const Options& o, Simulation& sim, RunOptions options) {
  if (o.stop) {
    auto own = std::move(options.stop);
    options.stop = [&o, own] { return o.stop() || (own && own()); };
  }
  RunResult r = run_simulation(sim, options);
  if (!r.completed) throw Interrupted();
  return r;
}

nlohmann::json stored_point(const Options& o, const nlohmann::json& what, bool reuse,
                            const std::function<nlohmann::json()>& compute) {
  const std::string defined = what.dump();
  const fs::path file = points_dir(o) / (point_key(what) + ".json");
  if (std::ifstream in(file); reuse && !o.out.empty() && in) {
    try {
      const nlohmann::json j = nlohmann::json::parse(in);
      if (j.at("what").dump() == defined) return j.at("result");
    } catch (const nlohmann::json::exception&) {
    }  // unreadable, or another point's: measure it again
  }
  stop_if_asked(o);
  const std::string text = nlohmann::json{{"what", what}, {"result", compute()}}.dump();
  if (!o.out.empty()) {
    std::error_code ec;  // write_text says when the folder is not there
    fs::create_directories(file.parent_path(), ec);
    write_text(file.string(), text + "\n");
  }
  return nlohmann::json::parse(text).at("result");
}

namespace {

// Every field of a timeseries row, in a fixed order (a stored point's rows).
template <class Row, class F>
void row_fields(Row& r, F&& f) {
  for (auto* v : {&r.t, &r.dp, &r.max_overlap_ratio, &r.max_wall_overlap_ratio,
                  &r.kinetic_energy, &r.mass_residual, &r.max_cfl, &r.fluid_force_y,
                  &r.energy.kinetic_translation, &r.energy.kinetic_rotation, &r.energy.potential,
                  &r.energy.spring_normal, &r.energy.spring_tangential, &r.energy.gas_work,
                  &r.energy.dashpot, &r.energy.friction, &r.energy.residual})
    f(*v);
  for (auto* v : {&r.pair_contacts, &r.wall_contacts, &r.simple_iterations, &r.bubbles}) f(*v);
}

// A number of a stored array; NaN where JSON has none (it writes NaN as null).
double number_at(const nlohmann::json& a, std::size_t k) {
  return a.at(k).is_number() ? a[k].get<double>() : NAN;
}

// A point's run: in the study's folder (points/KEY/, a run in a folder with its checkpoints, so
// that a stopped study continues the point where it stopped), or in memory without one.
PointRun measure_point(const Options& o, const fs::path& dir, const Settings& s, double until,
                       bool bubbles) {
  PointRun p;
  const auto start = std::chrono::steady_clock::now();
  if (o.out.empty()) {
    try {
      Simulation sim(s);
      RunOptions options;
      options.until = until;
      options.bubbles = bubbles;
      const double cpu0 = thread_cpu_seconds();
      p.result = run_to_end(o, sim, options);
      p.cpu = thread_cpu_seconds() - cpu0;
      p.ok = true;
    } catch (const SimulationFailure& e) {
      p.error = e.what();
      p.kind = failure_kind(p.error);
    }
  } else {
    RunJob job;
    job.scene = s;
    job.until = until;
    job.bubbles = bubbles;
    RunControl control;
    std::error_code ec;
    if (run_ended(dir.string())) fs::remove_all(dir, ec);  // its result was not kept: again
    control.resume = has_checkpoint(dir.string());
    control.stop = o.stop;
    RunEnd end = run_in_folder(dir.string(), job, control);
    if (end.how == RunEnd::How::stopped) throw Interrupted();
    p.ok = end.finished();
    p.cpu = end.cpu;
    if (p.ok) {
      p.result = std::move(end.result);
    } else {
      p.error = end.error;
      p.kind = failure_kind(p.error);
    }
  }
  p.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return p;
}

}  // namespace

nlohmann::json run_definition(const char* kind, const Settings& s, double until) {
  // A start state counts by its bytes, not where it is (a study's folder may move).
  Settings named = s;
  std::string start;
  if (s.particles.placement == Placement::State) {
    start = file_digest(s.particles.state_file);
    named.particles.state_file.clear();
  }
  return {{"point", kind},
          {"scene", to_toml(named)},
          {"threads", s.threads},
          {"start_state", start},
          {"until", until}};
}

nlohmann::json point_run_json(const PointRun& p) {
  nlohmann::json rows = nlohmann::json::array();
  for (const TimeseriesRow& r : p.result.rows) {
    nlohmann::json a = nlohmann::json::array();
    row_fields(r, [&](const auto& v) { a.push_back(v); });
    a.push_back(static_cast<int>(r.regime));
    rows.push_back(std::move(a));
  }
  return {{"ok", p.ok},     {"error", p.error}, {"kind", p.kind},
          {"wall_s", p.wall}, {"cpu_s", p.cpu},   {"summary", p.result.summary},
          {"rows", rows}};
}

PointRun point_run_from_json(const nlohmann::json& j) {
  PointRun p;
  p.ok = j.at("ok").get<bool>();
  p.error = j.at("error").get<std::string>();
  p.kind = j.at("kind").get<std::string>();
  p.wall = json_number(j, "wall_s");
  p.cpu = json_number(j, "cpu_s");
  p.result.summary = j.at("summary");
  for (const nlohmann::json& a : j.at("rows")) {
    TimeseriesRow r;
    std::size_t k = 0;
    row_fields(r, [&](auto& v) {
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>)
        v = number_at(a, k++);
      else
        v = a.at(k++).template get<int>();
    });
    r.regime = static_cast<Regime>(a.at(k).get<int>());
    p.result.rows.push_back(r);
  }
  return p;
}

PointRun run_point(const Options& o, const Settings& s, double until, bool bubbles) {
  nlohmann::json what = run_definition("run", s, until);
  const RunOptions checks;  // the run's own checks, at their defaults (part of what defines it)
  what["cfl_limit"] = checks.cfl_limit;
  what["porosity_min"] = checks.porosity_min;
  what["bubbles"] = bubbles;
  const fs::path dir = points_dir(o) / point_key(what);
  PointRun p = point_run_from_json(stored_point(
      o, what, true, [&] { return point_run_json(measure_point(o, dir, s, until, bubbles)); }));
  std::error_code ec;
  fs::remove_all(dir, ec);  // the point's record is kept: its run's folder is no longer needed
  return p;
}

double DecreasingBranch::dp_at(double U) const {
  for (std::size_t k = 0; k < u.size(); ++k)
    if (std::fabs(u[k] - U) < 5e-4) return dp[k];
  return NAN;
}

DecreasingBranch decreasing_branch(const Options& o, const Settings& s,
                                   const std::vector<double>& velocities, double run_time,
                                   double averaging) {
  nlohmann::json what = run_definition("decreasing_branch", s, run_time);
  std::vector<double> sorted = velocities;
  std::sort(sorted.begin(), sorted.end());
  what["velocities"] = sorted;
  what["averaging_start"] = averaging;
  const fs::path dir = points_dir(o) / point_key(what);
  const nlohmann::json j = stored_point(o, what, true, [&] {
    SweepOptions so = decreasing_branch_options(sorted, run_time, averaging, dir.string());
    so.resume = o.resume && fs::exists(dir / "sweep.json");
    so.stop = o.stop;
    const SweepResult r = run_sweep(s, so);
    if (r.interrupted) throw Interrupted();
    nlohmann::json out = {{"ok", r.umf.ok}, {"umf", r.umf.ok ? r.umf.umf : 0.0},
                          {"wall", r.wall_time}, {"u", nlohmann::json::array()},
                          {"dp", nlohmann::json::array()}};
    std::string why = r.umf.ok ? "" : "no U_mf: " + r.umf.why;
    for (const SweepPoint& p : way_down(r)) {
      if (p.ok) {
        out["u"].push_back(p.u);
        out["dp"].push_back(p.dp_mean);
      } else if (why.empty() && !p.error.empty() && p.error.rfind("not run", 0) != 0) {
        why = "a run failed: " + p.error;
      }
    }
    out["why"] = why;
    return out;
  });
  std::error_code ec;
  fs::remove_all(dir, ec);  // the point's record is kept: its runs' folders are no longer needed
  DecreasingBranch b;
  b.ok = j.at("ok").get<bool>();
  b.umf = b.ok ? j.at("umf").get<double>() : NAN;
  b.why = j.at("why").get<std::string>();
  b.wall = j.at("wall").get<double>();
  b.u = j.at("u").get<std::vector<double>>();
  b.dp = j.at("dp").get<std::vector<double>>();
  return b;
}

std::string failure_kind(const std::string& m) {
  auto has = [&](const char* w) { return m.find(w) != std::string::npos; };
  if (has("CFL")) return "cfl";
  if (has("porosity")) return "porosity";
  if (has("SIMPLE") || has("positive definite")) return "simple";
  if (has("NaN") || has("not finite") || has("overflowed")) return "nan";
  if (has("overlap")) return "overlap";
  if (has("left the bed")) return "left_bed";
  if (has("energy")) return "energy";
  return "other";
}

double fixed_bed_force_ratio(const Options& o, const Settings& fixed, double U, double time,
                             double& dp) {
  Settings s = fixed;
  s.inlet.superficial_velocity = U;
  Simulation sim(s);
  RunOptions opt;
  opt.until = time;
  run_to_end(o, sim, opt);
  const Particles& p = sim.dem().particles();
  double f = 0.0, m = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    f += p.ext_fy[i];
    m += p.mass[i];
  }
  dp = sim.pressure_drop();
  return f / (m * s.physics.gravity);
}

double fixed_bed_umf(const Options& o, const Settings& fixed, double lo, double hi, double time,
                     double& dp_lo) {
  nlohmann::json what = run_definition("fixed_bed_umf", fixed, time);
  what["bracket"] = {lo, hi};
  const nlohmann::json r = stored_point(o, what, true, [&] {
    bool first = true;  // false_position evaluates lo first: its dp is the caller's
    double dp_first = NAN;
    auto excess = [&](double U) {
      double dp = 0.0;
      const double f = fixed_bed_force_ratio(o, fixed, U, time, dp) - 1.0;
      if (first) dp_first = dp;
      first = false;
      return f;
    };
    const double umf = false_position(excess, lo, hi, 8, 0.002).secant_root();
    return nlohmann::json{{"umf", umf}, {"dp_lo", dp_first}};
  });
  dp_lo = json_number(r, "dp_lo");
  return json_number(r, "umf");
}

Settings bed_scene(Size size, const std::vector<std::string>& overrides) {
  std::vector<std::string> all;
  if (size == Size::Tiny)
    all = {"domain.width=0.06",        "domain.height=0.3",      "particles.count=300",
           "particles.fill_height=0.12", "particles.packing_time=0.3", "gas.cells_x=6",
           "gas.cells_y=15",           "diagnostics.probes=[[0.03, 0.10]]"};  // its centre line
  all.insert(all.end(), overrides.begin(), overrides.end());
  return load_scene(render::asset_dir() + "/scenes/xu_yu_1997.toml", all);
}

Settings bed_scene(const Options& o, const std::vector<std::string>& overrides) {
  Settings s = bed_scene(o.size, overrides);
  return o.seed ? with_seed(std::move(s), *o.seed) : s;
}

void Table::add(const std::vector<std::string>& row, bool failed) {
  if (row.size() != columns_.size())
    throw std::logic_error("study table: a row of " + std::to_string(row.size()) +
                           " values for " + std::to_string(columns_.size()) + " columns");
  rows_.push_back(row);
  failed_ += failed ? 1 : 0;
}

void write_table(const std::string& dir, const Table& t, Report& rep) {
  write_text((fs::path(dir) / "study.csv").string(), t.csv());
  rep.points += static_cast<int>(t.rows());
  rep.failed += t.failed();
}

double json_number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

double json_number(const nlohmann::json& j, const char* object, const char* key) {
  return j.is_object() && j.contains(object) ? json_number(j[object], key) : NAN;
}

Verdict judge(const std::vector<Bound>& bounds, const std::function<double(const char*)>& value,
              const std::function<double(const char*)>& two_se) {
  Verdict v;
  std::vector<std::string> off, missing, unsettled;
  for (const Bound& b : bounds) {
    const double x = value(b.column);
    if (!std::isfinite(x)) {
      if (std::find(missing.begin(), missing.end(), b.missing) == missing.end())
        missing.push_back(b.missing);
      continue;
    }
    if (x < b.lo || x > b.hi) off.push_back(std::string(b.name) + " off");
    if (two_se) {
      const double e = two_se(b.column);
      if (!(std::fabs(x - b.lo) > e && std::fabs(x - b.hi) > e)) unsettled.push_back(b.name);
    }
  }
  auto join = [](const std::vector<std::string>& parts) {
    std::string t;
    for (const auto& p : parts) t += (t.empty() ? "" : ", ") + p;
    return t;
  };
  off.insert(off.end(), missing.begin(), missing.end());
  v.within = off.empty();
  v.settled = unsettled.empty();
  v.text = v.within ? "within" : join(off);
  if (!v.settled) v.text += "; not settled: " + join(unsettled);
  return v;
}

Settings drop_scene(double y) {
  Settings s;
  s.scene.name = "drop";
  s.scene.kind = SceneKind::Drop;
  s.particles.count = 1;
  s.particles.placement = Placement::Single;
  s.particles.y = y;
  return s;
}

std::string Table::csv() const {
  std::string out;
  auto line = [&](const std::vector<std::string>& v) {
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (k) out += ',';
      out += csv_text(v[k]);
    }
    out += "\n";
  };
  line(columns_);
  for (const auto& r : rows_) line(r);
  return out;
}

void write_text(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& o) { o << text; });
}

namespace {
const chart::Font& font() {
  static const chart::Font f = chart::Font::load_default(render::asset_dir());
  return f;
}
}  // namespace

chart::Chart log_log_chart(const std::string& title, const std::string& x_label,
                           const std::string& y_label) {
  chart::Chart c;
  c.title = title;
  c.x.label = x_label;
  c.x.log = true;
  c.y.label = y_label;
  c.y.log = true;
  return c;
}

std::string write_chart(const std::string& dir, const std::string& file, const chart::Chart& c,
                        int width, int height) {
  chart::render(c, width, height, font()).write_png((fs::path(dir) / file).string());
  return file;
}

std::string write_grid(const std::string& dir, const std::string& file,
                       const std::vector<chart::Chart>& charts, int columns, int panel_w,
                       int panel_h, const std::string& title) {
  chart::render_grid(charts, columns, panel_w, panel_h, font(), title)
      .write_png((fs::path(dir) / file).string());
  return file;
}

}  // namespace fluidbed::app::study
