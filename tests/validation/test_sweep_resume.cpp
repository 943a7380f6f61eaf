// A sweep that is stopped resumes where it stopped (`sweep --resume DIR`): finished runs are read
// back from their records, a stopped run continues from its checkpoint, the rest run, and the
// sweep ends with the uninterrupted sweep's numbers, timeseries and final states, bit for bit. A
// changed scene or option refuses to resume, in one line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "run/run_folder.hpp"
#include "run/velocity_sweep.hpp"
#include "scene/scene_loader.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kSmallBed = {"particles.placement=lattice", "particles.count=150",
                                            "particles.fill_height=0.08", "inlet.kind=uniform"};

Settings small_bed(std::vector<std::string> more = {}) {
  std::vector<std::string> o = kSmallBed;
  o.insert(o.end(), more.begin(), more.end());
  return load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml", o);
}

// 3 velocities, 400 particle steps a run (5 runs, 2000 steps), one run at a time: a stop after a
// given number of steps falls at one place of one run.
SweepOptions small_sweep(const fs::path& dir) {
  SweepOptions o;
  o.velocities = {0.5, 1.0, 1.5};
  o.run_time = 0.006;
  o.averaging_start = 0.003;
  o.threads = 1;
  o.out_dir = dir.string();
  return o;
}

// `fluidbed sweep` of the small bed with `options`, into `dir` (its own output beside it).
std::string small_sweep_args(const std::string& options) {
  std::string args = std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml " + options;
  for (const auto& o : kSmallBed) args += " --set " + o;
  return args;
}

// `fluidbed sweep ARGS --out DIR` in the background, SIGTERM after `seconds`; the exit status.
int sweep_and_terminate(const std::string& args, const fs::path& dir, double seconds) {
  return fluidbed_terminated("sweep " + args + " --out \"" + dir.string() + "\"", dir,
                             after_seconds(seconds))
      .status;
}

void expect_same_point(const SweepPoint& a, const SweepPoint& b, const fs::path& da,
                       const fs::path& db) {
  const std::string what = a.branch + " " + std::to_string(a.u);
  EXPECT_EQ(a.ok, b.ok) << what;
  EXPECT_EQ(a.dp_mean, b.dp_mean) << what;
  EXPECT_EQ(a.dp_std, b.dp_std) << what;
  EXPECT_EQ(a.start_hash, b.start_hash) << what;
  EXPECT_EQ(a.end_hash, b.end_hash) << what;
  char name[64];
  std::snprintf(name, sizeof name, "%s-%.3f", a.branch.c_str(), a.u);
  for (const char* f : {"timeseries.csv", "final.state"})
    EXPECT_EQ(read_file(da / "runs" / name / f), read_file(db / "runs" / name / f)) << what << f;
}

}  // namespace

TEST(SweepResume, StoppedTwiceAndResumedGivesTheUninterruptedSweepsBits) {
  const Settings s = small_bed();
  const fs::path ref_dir = temp_dir("sweep-resume-ref");
  const SweepResult ref = run_sweep(s, small_sweep(ref_dir));
  ASSERT_FALSE(ref.interrupted);

  // The runs go: up 1.5 (steps 1-400), down 1.0 (401-800), down 0.5, up 0.5, up 1.0. A stop at
  // step 600 falls inside down 1.0 (a run that starts from another run's final state); the next,
  // 700 steps into the resumed sweep, inside up 0.5 (down 1.0's other 200 steps, down 0.5's 400).
  const fs::path dir = temp_dir("sweep-resume");
  SweepOptions o = small_sweep(dir);
  long asked = 0;
  o.stop = [&] { return ++asked > 600; };
  const SweepResult first = run_sweep(s, o);
  EXPECT_TRUE(first.interrupted);
  EXPECT_TRUE(first.up[2].ok);
  EXPECT_TRUE(first.down[1].interrupted);
  EXPECT_TRUE(fs::is_directory(dir / "runs/down-1.000/checkpoint"));
  EXPECT_FALSE(run_ended((dir / "runs/down-1.000").string()));  // no finished marker

  o.resume = true;
  asked = 0;
  o.stop = [&] { return ++asked > 700; };
  const SweepResult second = run_sweep(s, o);
  EXPECT_TRUE(second.interrupted);
  EXPECT_TRUE(second.up[2].resumed);  // read back
  EXPECT_TRUE(second.down[1].resumed && second.down[1].ok);  // continued from its checkpoint
  EXPECT_TRUE(second.down[0].ok && !second.down[0].resumed);
  EXPECT_TRUE(second.up[0].interrupted);

  o.stop = nullptr;
  const SweepResult last = run_sweep(s, o);
  ASSERT_FALSE(last.interrupted);
  for (std::size_t k = 0; k < 3; ++k) expect_same_point(ref.up[k], last.up[k], ref_dir, dir);
  for (std::size_t k = 0; k < 2; ++k) expect_same_point(ref.down[k], last.down[k], ref_dir, dir);
  EXPECT_EQ(ref.umf.ok, last.umf.ok);
  EXPECT_FALSE(fs::exists(dir / "runs/up-0.500/checkpoint"));  // a finished run keeps none

  // Another scene or other options than the sweep's: refused, naming what changed.
  SweepOptions other = small_sweep(dir);
  other.resume = true;
  try {
    run_sweep(small_bed({"particles.density=2000"}), other);
    ADD_FAILURE() << "a changed scene was resumed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("density"), std::string::npos) << e.what();
  }
  other.run_time = 0.01;
  EXPECT_THROW(run_sweep(s, other), InputError);
}

TEST(SweepResume, CommandLineSigtermThenResume) {
  // The same small bed with runs of 0.1 s (about a second each): SIGTERM after 1.5 s stops the
  // sweep inside its second run; `sweep --resume DIR` finishes it with the numbers of a sweep
  // that was never stopped.
  const std::string args =
      small_sweep_args("--velocities 0.5,1.0,1.5 --run-time 0.1 --averaging-start 0.05 --threads 1");
  const fs::path ref = temp_dir("sweep-cli-ref"), dir = temp_dir("sweep-cli");
  const CommandResult r = run_fluidbed("sweep " + args + " --out " + ref.string(), "sweep-cli-ref");
  ASSERT_EQ(r.status, 0) << r.err;

  EXPECT_EQ(sweep_and_terminate(args, dir, 1.5), 130);
  const std::string err = read_file(dir / "err.txt");
  EXPECT_NE(err.find("resume with: fluidbed sweep --resume " + dir.string()), std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir / "summary.json"));  // an unfinished sweep has none

  // Options beside --resume, a folder without a sweep: one line, status 2.
  for (const std::string& bad : {"sweep --resume " + dir.string() + " --run-time 3",
                                 "sweep --resume " + ref.parent_path().string()}) {
    const CommandResult b = run_fluidbed(bad, "sweep-cli-bad");
    EXPECT_EQ(b.status, 2) << bad;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << b.err;
  }

  const CommandResult resumed = run_fluidbed("sweep --resume " + dir.string(), "sweep-cli-resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  auto points = [](const fs::path& d) {
    nlohmann::json p = nlohmann::json::parse(read_file(d / "summary.json"))["points"];
    for (auto& x : p) x.erase("wall_time_s");
    return p;
  };
  EXPECT_EQ(points(ref), points(dir));
}

TEST(SweepResume, EnsembleOfTwoSeedsResumesSeedBySeed) {
  // `sweep --seeds 2` of the small bed (runs of 0.05 s): SIGTERM after 1 s stops it in the first
  // seed's sweep; the resumed ensemble's summary equals the uninterrupted one's.
  const std::string args = small_sweep_args(
      "--velocities 0.5,1.0,1.5 --run-time 0.05 --averaging-start 0.02 --threads 1 --seeds 2");
  const fs::path ref = temp_dir("sweep-seeds-ref"), dir = temp_dir("sweep-seeds");
  const CommandResult r = run_fluidbed("sweep " + args + " --out " + ref.string(), "sweep-seeds");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(sweep_and_terminate(args, dir, 1.0), 130) << read_file(dir / "err.txt");
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  const CommandResult resumed = run_fluidbed("sweep --resume " + dir.string(), "sweep-seeds-resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  auto ensemble = [](const fs::path& d) {
    nlohmann::json e = nlohmann::json::parse(read_file(d / "summary.json"))["ensemble"];
    for (auto it = e.begin(); it != e.end();)
      it = it.key().find("wall") != std::string::npos ? e.erase(it) : std::next(it);
    return e;
  };
  EXPECT_EQ(ensemble(ref), ensemble(dir));
  int seeds = 0;
  for (const auto& e : fs::directory_iterator(ref / "seeds")) {
    const fs::path run = fs::path("seeds") / e.path().filename() / "runs/down-0.500/timeseries.csv";
    EXPECT_EQ(read_file(ref / run), read_file(dir / run)) << run;
    ++seeds;
  }
  EXPECT_EQ(seeds, 2);
}
