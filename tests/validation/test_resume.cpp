// Checkpoints and resume (`run --resume DIR`): a run stopped by SIGTERM writes DIR/checkpoint/,
// says how to resume in one line and exits 130; resumed, it ends with the same timeseries.csv,
// the same summary.json numbers (wall-time fields excepted) and the same state hash as the run
// that was never stopped, wherever the stop fell, a gas sub-step cycle's middle included. A
// changed scene, a folder without a checkpoint or a path that is no folder refuses in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "run/checkpoint.hpp"
#include "run/run_loop.hpp"
#include "scene/scene_loader.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

fs::path write_scene(const fs::path& dir) {
  const fs::path p = dir / "small.toml";
  write_file(p, small_jet_bed_toml("resume-test"));
  return p;
}

// Appended rather than "\"" + p.string(): GCC 12 warns falsely (-Wrestrict) on the latter.
std::string quoted(const fs::path& p) {
  std::string q(1, '"');
  q += p.string();
  q += '"';
  return q;
}

// `fluidbed run SCENE --out DIR` in the background, SIGTERM `delay` seconds after the run has
// begun stepping (DIR/scene.toml is written just before the interrupt handler and the first step);
// the exit status.
int run_and_terminate(const fs::path& scene, const fs::path& dir, double delay) {
  char sleep_s[32];
  std::snprintf(sleep_s, sizeof sleep_s, "%.3f", delay);
  const std::string started = quoted(dir / "scene.toml");
  const std::string cmd = "sh -c '\"" + std::string(FLUIDBED_BINARY) + "\" run " + quoted(scene) +
                          " --out " + quoted(dir) + " > " + quoted(dir / "out.txt") + " 2> " +
                          quoted(dir / "err.txt") + " & p=$!; while [ ! -e " + started +
                          " ] && kill -0 $p 2> /dev/null; do sleep 0.005; done; sleep " + sleep_s +
                          "; kill -TERM $p 2> /dev/null; wait $p; echo $? > " +
                          quoted(dir / "rc.txt") + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  return std::stoi(read_file(dir / "rc.txt"));
}

// `fluidbed run SCENE --out DIR` to its end; the wall seconds of its steps.
double timed_run(const fs::path& scene, const fs::path& out) {
  const CommandResult r =
      run_fluidbed("run " + quoted(scene) + " --out " + quoted(out), "resume-ref");
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(read_file(out / "summary.json"))["wall_time_s"].get<double>();
}

// A run folder's file names, without those the test's shell writes into it.
std::set<std::string> file_names(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  for (const char* shell : {"out.txt", "err.txt", "rc.txt"}) names.erase(shell);
  return names;
}

// summary.json without what measures the machine rather than the run.
nlohmann::json run_numbers(const fs::path& dir) {
  nlohmann::json j = nlohmann::json::parse(read_file(dir / "summary.json"));
  for (const char* k : {"wall_time_s", "wall_s_per_sim_s", "particle_steps_per_s"}) j.erase(k);
  return j;
}

// The engine's side alone, stopped at an exact step: the run to `stop_step` with a checkpoint at
// the stop, then a new simulation of the same scene (or of `resume_as`) resumed from it to the
// end. `since_gas`: the particle steps between the last gas step and the stop.
RunResult stopped_and_resumed(const Settings& s, std::int64_t stop_step, const fs::path& dir,
                              int* since_gas = nullptr, const Settings* resume_as = nullptr) {
  Simulation first(s);
  RunOptions o;
  o.stop = [&] { return first.steps() == stop_step; };
  o.checkpoint = [&](const Simulation& x, const RunRecorder& rec, double wall) {
    write_checkpoint(dir.string(), x, rec, wall, to_toml(s), nlohmann::json::object(), false);
  };
  EXPECT_FALSE(run_simulation(first, o).completed);
  const Checkpoint c = read_checkpoint(dir.string());
  Simulation second(resume_as ? *resume_as : s);
  restore_simulation(c, second);
  EXPECT_EQ(second.steps(), stop_step);
  if (since_gas) *since_gas = second.steps_since_gas_step();
  RunOptions resumed;
  resumed.restore = [&](RunRecorder& rec) { restore_recorder(c, rec); };
  return run_simulation(second, resumed);
}

void expect_same_run(const RunResult& a, const RunResult& b) {
  nlohmann::json x = a.summary, y = b.summary;
  for (const char* k : {"wall_time_s", "wall_s_per_sim_s", "particle_steps_per_s"}) {
    x.erase(k);
    y.erase(k);
  }
  EXPECT_EQ(x, y);
  EXPECT_EQ(
      timeseries_header(false) +
          [&] {
            std::string t;
            for (const auto& r : a.rows) t += timeseries_line(r, false);
            return t;
          }(),
      timeseries_header(false) +
          [&] {
            std::string t;
            for (const auto& r : b.rows) t += timeseries_line(r, false);
            return t;
          }());
}

}  // namespace

// Exact steps: on a gas step, inside a gas cycle (7 particle steps after a gas step) and one more,
// and a drop test stopped at three points of its bounces (its bounce tracker is in the checkpoint).
TEST(Resume, EngineCheckpointAtAnyStepIsBitExact) {
  const fs::path dir = temp_dir("resume-engine");
  Settings bed = load_scene(write_scene(dir).string());
  bed.time.end = 0.04;
  Simulation whole(bed);
  std::int64_t on_gas_step = -1, mid_cycle = -1;  // the first of each after steps 1000 and 2000
  RunOptions watch;
  watch.on_step = [&](const Simulation& x) {
    if (on_gas_step < 0 && x.steps() > 1000 && x.steps_since_gas_step() == 0)
      on_gas_step = x.steps();
    if (mid_cycle < 0 && x.steps() > 2000 && x.steps_since_gas_step() == 7) mid_cycle = x.steps();
  };
  const RunResult ref = run_simulation(whole, watch);
  ASSERT_GT(on_gas_step, 0);
  ASSERT_GT(mid_cycle, 0);
  for (std::int64_t stop : {on_gas_step, mid_cycle, std::int64_t{1803}}) {
    SCOPED_TRACE(stop);
    int since_gas = -1;
    expect_same_run(stopped_and_resumed(bed, stop, dir, &since_gas), ref);
    if (stop == on_gas_step) {
      EXPECT_EQ(since_gas, 0);
    }
    if (stop == mid_cycle) {
      EXPECT_EQ(since_gas, 7);
    }
  }
  Settings drop = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/drop.toml");
  drop.time.end = 0.15;
  Simulation whole_drop(drop);
  const RunResult ref_drop = run_simulation(whole_drop, RunOptions{});
  ASSERT_FALSE(ref_drop.summary["bounce_restitutions"].empty());
  for (std::int64_t stop : {2000, 4321, 7777}) {
    SCOPED_TRACE(stop);
    expect_same_run(stopped_and_resumed(drop, stop, dir), ref_drop);
  }
}

// With pressure probes: their columns, the bed top and the probes' summary come out of a stopped
// and resumed run as out of one never stopped (the rows are saved with their probes' values).
TEST(Resume, ProbesResumeBitExact) {
  const fs::path dir = temp_dir("resume-probes");
  Settings bed = load_scene(write_scene(dir).string(),
                            {"diagnostics.probes=[[0.045, 0.015], [0.075, 0.1]]"});
  bed.time.end = 0.06;
  Simulation whole(bed);
  const RunResult ref = run_simulation(whole, RunOptions{});
  ASSERT_EQ(ref.rows.back().probes.size(), 2u);
  ASSERT_TRUE(ref.summary.contains("probes"));
  for (std::int64_t stop : {std::int64_t{1803}, std::int64_t{2900}}) {
    SCOPED_TRACE(stop);
    const RunResult resumed = stopped_and_resumed(bed, stop, dir);
    expect_same_run(resumed, ref);
    ASSERT_EQ(resumed.rows.size(), ref.rows.size());
    for (std::size_t k = 0; k < ref.rows.size(); ++k)
      ASSERT_EQ(resumed.rows[k].probes, ref.rows[k].probes) << "row " << k;
  }
  // A checkpoint of a run with probes is refused by a recorder without them.
  Settings plain = bed;
  plain.diagnostics.probes.clear();
  EXPECT_THROW(stopped_and_resumed(bed, 1000, dir, nullptr, &plain), InputError);
}

// The program's side with probes: a run stopped by SIGTERM and resumed writes the timeseries
// (its probe columns from the checkpoint's rows and the live file's header), the summary and
// dp_spectrum.csv of the run never stopped.
TEST(Resume, SigtermThenResumeWithProbes) {
  const fs::path dir = temp_dir("resume-probes-cli");
  const fs::path scene = dir / "probes.toml";
  std::string text = read_file(write_scene(dir));
  const std::string last = "averaging_start = 0.04\n";
  text.replace(text.find(last), last.size(), last + "probes = [[0.045, 0.015], [0.075, 0.1]]\n");
  write_file(scene, text);
  const fs::path ref = dir / "reference";
  const double whole = timed_run(scene, ref);
  ASSERT_NE(read_file(ref / "timeseries.csv").find(",bed_top,p_probe_1,p_probe_2\n"),
            std::string::npos);
  int stopped = 0;
  for (int attempt = 0; attempt < 8 && stopped < 1; ++attempt) {
    const fs::path run = dir / ("run" + std::to_string(attempt));
    fs::create_directories(run);
    const int rc = run_and_terminate(scene, run, whole * (0.3 + 0.05 * attempt));
    if (rc == 0) continue;  // finished before the signal
    ASSERT_EQ(rc, 130) << read_file(run / "err.txt");
    ++stopped;
    const CommandResult resumed = run_fluidbed("run --resume " + quoted(run), "resume-probes");
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    EXPECT_EQ(read_file(run / "timeseries.csv"), read_file(ref / "timeseries.csv"));
    EXPECT_EQ(read_file(run / "dp_spectrum.csv"), read_file(ref / "dp_spectrum.csv"));
    EXPECT_EQ(run_numbers(run), run_numbers(ref));
  }
  EXPECT_EQ(stopped, 1);
}

TEST(Resume, SigtermThenResumeGivesTheUninterruptedRunsBits) {
  const fs::path dir = temp_dir("resume-bits");
  const fs::path scene = write_scene(dir);
  const fs::path ref = dir / "reference";
  const double whole = timed_run(scene, ref);
  std::printf("uninterrupted run: %.2f s of steps\n", whole);

  // Stops at several wall times: whichever step each falls after, the resumed run must end with
  // the reference's bits. At least one stop must fall inside a gas cycle (between two gas steps)
  // and one at another step; more tries if chance denies it.
  int stopped = 0, mid_cycle = 0;
  std::set<long long> steps_seen;
  for (int attempt = 0; attempt < 16 && (stopped < 2 || mid_cycle < 1); ++attempt) {
    const fs::path run = dir / ("run" + std::to_string(attempt));
    fs::create_directories(run);
    // Between 10 % and 82 % of the way through the steps.
    const double delay = whole * (0.1 + 0.08 * (attempt * 7 % 10));
    const int rc = run_and_terminate(scene, run, delay);
    if (rc == 0) continue;  // finished before the signal (a slower machine than the reference's)
    const std::string err = read_file(run / "err.txt");
    ASSERT_EQ(rc, 130) << err;
    ASSERT_EQ(err.rfind("interrupted at t = ", 0), 0u) << err;
    EXPECT_NE(err.find("; resume with: fluidbed run --resume " + run.string()), std::string::npos)
        << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_FALSE(fs::exists(run / "summary.json"));
    ASSERT_TRUE(fs::exists(run / "checkpoint" / "state.bin"));
    const auto where = nlohmann::json::parse(read_file(run / "checkpoint" / "where.json"));
    const long long step = where["step"].get<long long>();
    const int since_gas = where["steps_since_gas_step"].get<int>();
    if (!steps_seen.insert(step).second) continue;
    ++stopped;
    if (since_gas != 0) ++mid_cycle;
    std::printf("stopped after step %lld (%d particle steps after a gas step)\n", step, since_gas);

    const CommandResult resumed = run_fluidbed("run --resume " + quoted(run), "resume-run");
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    EXPECT_EQ(read_file(run / "timeseries.csv"), read_file(ref / "timeseries.csv"))
        << "step " << step;
    EXPECT_EQ(run_numbers(run), run_numbers(ref)) << "step " << step;
    EXPECT_EQ(nlohmann::json::parse(read_file(run / "status.json"))["status"], "completed");
    // The finished folder holds an unstopped run's files (beside the shell's captures).
    EXPECT_EQ(file_names(run), file_names(ref)) << "step " << step;
  }
  EXPECT_GE(stopped, 2);
  EXPECT_GE(mid_cycle, 1);
}

TEST(Resume, RefusesAChangedSceneAMissingCheckpointAndBadPaths) {
  const fs::path dir = temp_dir("resume-refuse");
  const fs::path scene = write_scene(dir);
  const fs::path run = dir / "run";
  fs::create_directories(run);
  const int rc = run_and_terminate(scene, run, 0.01);  // as soon as it steps
  ASSERT_EQ(rc, 130) << read_file(run / "err.txt");
  auto refused = [](const CommandResult& c, const std::string& words) {
    EXPECT_EQ(c.status, 2) << c.err;
    EXPECT_EQ(std::count(c.err.begin(), c.err.end(), '\n'), 1) << c.err;
    EXPECT_NE(c.err.find(words), std::string::npos) << c.err;
  };
  refused(
      run_fluidbed("run " + quoted(scene) + " --set particles.density=1350 --resume " + quoted(run),
                   "resume-changed"),
      "density");
  refused(run_fluidbed("run --resume " + quoted(run) + " --until 0.5", "resume-until"), "--until");
  const fs::path empty = dir / "empty";
  fs::create_directories(empty);
  refused(run_fluidbed("run --resume " + quoted(empty), "resume-empty"), "no checkpoint");
  refused(run_fluidbed("run --resume " + quoted(scene), "resume-file"), "not a folder");
  refused(run_fluidbed("run --resume " + quoted(dir / "missing"), "resume-missing"),
          "no such folder");
  // The refusals left the checkpoint as it was: the run still resumes.
  const CommandResult ok = run_fluidbed("run --resume " + quoted(run), "resume-after-refusals");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_TRUE(fs::exists(run / "summary.json"));
}
