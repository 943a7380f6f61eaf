#pragma once
// Studies: speed against accuracy, stability limits and model choices, measured by the program
// itself (`fluidbed study NAME --out DIR`). Each study reads in four steps: it measures its
// points (side by side on a RunPool, core/run_pool.hpp, each simulation on one thread), builds
// the table DIR/study.csv (every point a row; a failed run is a row with its reason, never a
// crash), draws its charts as PNG, and writes the summary (DIR/summary.md): what was measured,
// the key figures, and what a user should choose.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "chart/chart.hpp"
#include "dem/contact_law.hpp"
#include "run/run_loop.hpp"
#include "scene/settings.hpp"
#include "core/json_fields.hpp"
#include "core/run_pool.hpp"
#include "core/text_format.hpp"

namespace fluidbed::app::study {

enum class Size { Tiny, Full };

struct Options {
  std::string out;  // folder for study.csv, the charts and summary.md (created)
  Size size = Size::Full;
  int workers = 0;  // points at once; 0: one per core
  // Progress lines (may be empty); run_study hands the study one that its points' threads may
  // call at the same time.
  std::function<void(const std::string&)> log;
  // Resume the study in `out` (run_study: InputError of one line when out holds no study, or
  // another study or size); without it run_study starts afresh and forgets out's points.
  bool resume = false;
  // Asked before every point and after every step of one: true stops the study there (the
  // point being measured throws Interrupted and is kept by no one; finished points stay).
  std::function<bool()> stop;
  std::string command;  // how the caller started the study (kept in DIR/study.json)
  // A member of `study NAME --seeds`: its bed (bed_scene(Options)) starts from the packing of
  // this lattice seed instead of the scene's own.
  std::optional<std::uint64_t> seed;
  // A study of a scene the user names (Info::takes_scene; `study sensitivity`): the scene file,
  // its --set, the --vary texts (studies/sensitivity.hpp), the end time in s (0: the scene's
  // time.end) and --seeds ("": the scene's own packing only).
  struct SceneStudy {
    std::string scene;
    std::vector<std::string> overrides, vary;
    double until = 0.0;
    std::string seeds;
  };
  SceneStudy scene_study;
};

// A study stopped by Options::stop: it wrote no study.csv, summary.md or status.json.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("study interrupted") {}
};

// What a study hands back; also written as DIR/summary.md (and used by `reproduce`).
struct Report {
  std::string name, title;
  std::vector<std::string> charts;  // PNG files inside the study's folder
  std::string findings;             // markdown: what was measured and the key figures
  std::string advice;               // one paragraph: what to choose and why (from the data)
  int points = 0, failed = 0;
  double wall_time = 0.0;  // s
};

// A bound a study's figure must keep: the number in study.csv's COLUMN within [lo, hi] (-inf or
// inf for one side). `name` is how a verdict names it ("frequency off"); `missing` is the verdict
// where the point has no such number ("no bubbles": a bed too small or calm to bubble passes
// nothing).
struct Bound {
  const char* column;
  const char* name;
  double lo, hi;
  const char* missing;
};

struct Info {
  const char* name;
  const char* title;
  const char* full_duration;  // how long the full size takes on two cores
  const char* tiny_duration;
  Report (*run)(const Options&);
  // Its findings hang on the packed bed's behaviour (bubbling, dp, U_mf): `--seeds` runs it over
  // several packings.
  bool over_packings = false;
  // Bounds its points are judged by (study.csv has a verdict column): with `--seeds`, the
  // ensemble summary judges every point by them over the seeds (write_study_ensemble).
  std::vector<Bound> bounds = {};
  // It studies a scene the user names (Options::scene_study) instead of its own: `reproduce`
  // leaves it out, and it takes --seeds itself (each point over the packings).
  bool takes_scene = false;
};

// A point judged by bounds: `value(column)` its number (NaN: none), `two_se(column)` two
// standard errors of it (an ensemble's mean; absent for a single run). Off where the number lies
// outside a bound; not settled where a bound lies within two standard errors of it (or the
// error is unknown), so that the ensemble cannot say on which side it falls.
struct Verdict {
  bool within = false;   // every number there and inside its bound
  bool settled = true;   // no bound within two standard errors
  std::string text;      // "within", "frequency off, no bubbles", "within; not settled: eruptions"
};
Verdict judge(const std::vector<Bound>& bounds, const std::function<double(const char*)>& value,
              const std::function<double(const char*)>& two_se = {});

// Every study, in the order.
const std::vector<Info>& all_studies();
// nullptr when no study has that name.
const Info* find_study(const std::string& name);
// Runs a study (creating its folder, timing it, writing summary.md); throws InputError for bad
// options or a resume that does not fit, Interrupted when Options::stop stopped it. Its points
// are kept as they finish in DIR/points (stored_point), and DIR/study.json says which study and
// size they belong to: Options::resume reads the finished points back and measures the rest.
Report run_study(const Info& info, const Options& o);
// With o.resume: InputError (one line, naming what differs) unless o.out holds a study that
// run_study(info, o) would resume. Callers check before they touch the folder.
void check_study_resume(const Info& info, const Options& o);
// What a study of a scene (Info::takes_scene) in DIR was started with (its study.json), for a
// resume that does not repeat it; InputError of one line when DIR holds none.
Options::SceneStudy stored_scene_study(const std::string& dir);
// The report a finished study left in its folder (its finished marker DIR/status.json, written
// last by run_study with the report and the size it ran at): `reproduce --resume` keeps it instead of running the study again.
// Nothing when there is none, it is unreadable, or it is of another size.
std::optional<Report> finished_study(const std::string& dir, Size size);

// ---- shared by the studies ----------------------------------------------------------------

// The paper's sphere: 4 mm glass, 9.048e-5 kg.
double paper_particle_mass();
// Every study takes the contact duration of a sphere against a wall, contact_duration(kappa, m)
// of dem/contact_law.hpp (1.34e-4 s at kappa = 50,000 N/m, as model.md derives; the paper's step
// is about 1/9 of it). A pair of equal spheres (reduced mass m/2) lasts 1/sqrt(2) as long.

// CPU seconds used by the calling thread so far. A point's cost is measured with it: each point
// runs on one thread, so this is its compute time whatever else shares the cores (on an idle core
// it equals the wall time; with other programs running, wall time measures the scheduler).
double thread_cpu_seconds();

// A point's result, kept in the study's folder: DIR/points/KEY.json, KEY the hash (Fnv1a) of
// `what` (everything that defines the point: its kind, the settings as TOML, the end time, the
// options that change its numbers). Read back when there (a resumed study); otherwise `compute`
// runs and its result is written (complete or not at all) before it is returned. Either way the
// caller gets the JSON as read from the file, so a point measured now and one read back give the
// same numbers (measured costs included: a point read back keeps its stored cost). compute may
// throw Interrupted (nothing is kept). With an empty o.out nothing is kept. reuse = false
// measures it again even when kept (a point whose files beside it are gone).
nlohmann::json stored_point(const Options& o, const nlohmann::json& what, bool reuse,
                            const std::function<nlohmann::json()>& compute);
// What defines a run of `s` to `until` (s) for stored_point: KIND, the settings as TOML, the
// threads inside a step and the bytes of a start state (not its path).
nlohmann::json run_definition(const char* kind, const Settings& s, double until);
// Throws Interrupted when o.stop says so (before a point).
void stop_if_asked(const Options& o);
// run_simulation(sim, options) that o.stop ends after any step: then Interrupted.
RunResult run_to_end(const Options& o, Simulation& sim, RunOptions options);

// A run that may fail: the failure's words and its kind instead of an exception.
struct PointRun {
  bool ok = false;
  std::string error;  // one line
  std::string kind;   // failure_kind(error)
  RunResult result;   // when ok
  double wall = 0.0;  // s, the whole point
  double cpu = 0.0;   // s, thread CPU time of run_simulation (the cost)
};
// Runs `s` to `until` (s), with the bubble analysis when asked; SimulationFailure becomes a failed
// point. A stored point (stored_point): of the result it keeps `summary` and `rows` (not the
// bubble rows, mixing or spectrum). It runs as a run in a folder (run/run_folder.hpp) in
// DIR/points/KEY/, removed once the point is kept: a point stopped midway keeps its checkpoint
// there, and the resumed study continues it from that step.
PointRun run_point(const Options& o, const Settings& s, double until, bool bubbles = false);
nlohmann::json point_run_json(const PointRun& p);
PointRun point_run_from_json(const nlohmann::json& j);

// What a failure message says, as one word: "nan", "overlap", "left_bed", "cfl", "porosity",
// "simple", "energy" or "other".
std::string failure_kind(const std::string& message);

// The paper's bed (xu_yu_1997.toml); Tiny: 300 particles in a bed 0.06 m wide and 0.3 m high with
// 6 x 15 gas cells of the paper's size and a 0.3 s packing.
Settings bed_scene(Size size, const std::vector<std::string>& overrides = {});
// The same for a study's options: from the packing of o.seed when set (a member of --seeds).
Settings bed_scene(const Options& o, const std::vector<std::string>& overrides = {});

// `study NAME --seeds`: the members' tables side by side, written into DIR (the members in
// DIR/seeds/S/, each a whole study): DIR/ensemble.csv, one row per point and numeric column of
// study.csv with its mean, standard deviation (n - 1), min, max and n over the seeds; and
// DIR/summary.md, which names every difference from the first point that is smaller than one
// run's spread (single runs cannot tell those apart) and says whether the ensemble resolves it
// (the difference taken seed by seed, its mean beyond Student's t at 95 % times its standard
// error). InputError when the members' tables differ in their columns or points, or have none.
void write_study_ensemble(const Info& info, const std::string& dir,
                          const std::vector<std::uint64_t>& seeds, Size size);

// The bed of `fixed` (particles.frozen, a uniform inlet) at inflow U after `time` s of gas: the
// fluid force on the particles over their weight, and dp (Pa).
double fixed_bed_force_ratio(const Options& o, const Settings& fixed, double U, double time,
                             double& dp);
// The model's minimum fluidization velocity: where that ratio reaches 1, by secant steps from the
// bracket [lo, hi] (m/s) to 2 mm/s. dp_lo: dp at lo. A stored point (stored_point).
double fixed_bed_umf(const Options& o, const Settings& fixed, double lo, double hi, double time,
                     double& dp_lo);

// A decreasing branch of the velocity sweep (run/velocity_sweep.hpp, decreasing_only) of `s` at
// VELOCITIES (m/s, any order), RUN_TIME s per velocity averaged from AVERAGING s: U_mf of its fit
// and dp of every run of the branch. A stored point (stored_point); the sweep runs in
// DIR/points/KEY/, resumed with the study and removed once the point is kept. Runs one run at a
// time (a point of a study runs beside the others).
struct DecreasingBranch {
  bool ok = false;            // the fit found U_mf
  std::string why;            // when not: the fit's reason or a failed run's
  double umf = NAN;           // m/s
  std::vector<double> u, dp;  // the branch's finished runs (m/s, Pa), increasing velocity
  double wall = 0.0;          // s
  // dp of the run at velocity U (to 1 mm/s); NaN when it did not finish.
  double dp_at(double U) const;
};
DecreasingBranch decreasing_branch(const Options& o, const Settings& s,
                                   const std::vector<double>& velocities, double run_time,
                                   double averaging);

// The table behind study.csv: named columns, rows of text, one a point.
class Table {
 public:
  explicit Table(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  // A point; FAILED: a failed run (counted in the report). Throws std::logic_error on a wrong
  // length.
  void add(const std::vector<std::string>& row, bool failed = false);
  std::string csv() const;
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_.size(); }
  int failed() const { return failed_; }

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
  int failed_ = 0;
};
// DIR/study.csv, and its points and failed runs counted into the report.
void write_table(const std::string& dir, const Table& t, Report& rep);

// A number of a run's summary.json; NaN when it is missing or not a number.
double json_number(const nlohmann::json& j, const char* key);
// A number of one of its objects (`dp_spectrum`, `bubbles`); NaN when either is missing.
double json_number(const nlohmann::json& j, const char* object, const char* key);

// A point's result as JSON and back (stored_point), through its field list
// (core/json_fields.hpp).
template <class T, class Fields>
T fields_from_json(const nlohmann::json& j, Fields&& fields) {
  T r;
  fluidbed::fields_from_json(j, r, fields);
  return r;
}

// A point kept in the study's store as its fields: COMPUTE's result (a T) stored under WHAT, or
// the stored one read back (stored_point, common.cpp).
template <class T, class Fields, class Compute>
T stored_fields(const Options& o, const nlohmann::json& what, Fields&& fields, Compute&& compute) {
  return fields_from_json<T>(
      stored_point(o, what, true, [&] { return fields_json(compute(), fields); }), fields);
}

// The drop scene: one particle released at height Y (m) above the floor's wall, no gas.
Settings drop_scene(double y);

// The program's number formats (core/text_format.hpp) under the studies' short names: %.6g and
// empty for NaN (a value that does not exist for a failed point); printf of one number; a CSV
// field.
inline std::string num(double v) { return table_number(v); }
inline std::string fmt(const char* format, double v) { return format_number(format, v); }
// A value as a scene file writes it so that it reads back bit for bit (17 significant digits).
inline std::string exact(double v) { return fmt("%.17g", v); }
inline std::string csv_text(std::string s) { return csv_field(std::move(s)); }

void write_text(const std::string& path, const std::string& text);
// A chart with both axes logarithmic (errors and costs against steps or costs).
chart::Chart log_log_chart(const std::string& title, const std::string& x_label,
                           const std::string& y_label);
// Draws one chart (or a grid of them) as PNG; returns the file name for the report.
std::string write_chart(const std::string& dir, const std::string& file, const chart::Chart& c,
                        int width = 1200, int height = 750);
std::string write_grid(const std::string& dir, const std::string& file,
                       const std::vector<chart::Chart>& charts, int columns, int panel_w,
                       int panel_h, const std::string& title);

// A study's four steps over what it measured (its Measured type): measure the points, build the
// table, draw the charts, write the summary (findings and advice). run_steps carries them out in
// that order and writes study.csv; it is the whole of a study's entry point.
template <class Measured>
struct Steps {
  std::function<Measured(const Options&)> measure;
  std::function<Table(const Measured&)> table;
  std::function<std::vector<std::string>(const Measured&, const std::string& dir)> charts;
  std::function<std::string(const Measured&)> findings, advice;
};

template <class Measured>
Report run_steps(const Options& o, const Steps<Measured>& steps) {
  const Measured m = steps.measure(o);
  Report rep;
  write_table(o.out, steps.table(m), rep);
  rep.charts = steps.charts(m, o.out);
  rep.findings = steps.findings(m);
  rep.advice = steps.advice(m);
  return rep;
}

// The studies.
Report integrators_study(const Options& o);
Report contact_study(const Options& o);
Report stiffness_study(const Options& o);
Report coupling_study(const Options& o);
Report modules_study(const Options& o);
Report model_form_study(const Options& o);
Report failures_study(const Options& o);
Report energy_study(const Options& o);
Report teaching_study(const Options& o);
Report sensitivity_study(const Options& o);  // studies/sensitivity.hpp
// The bounds the teaching scene was chosen by (docs/studies.md), as teaching_study's columns.
const std::vector<Bound>& teaching_bounds();

}  // namespace fluidbed::app::study
