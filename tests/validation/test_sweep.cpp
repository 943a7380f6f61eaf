// The velocity sweep's logic (branch order, state hand-over) on a small fast bed, and the
// minimum-fluidization fit on synthetic curves with known answers.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "run/velocity_sweep.hpp"
#include "analysis/umf_fit.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

using namespace fluidbed;

namespace {

// The paper's bed cut to 150 particles on the lattice start with a uniform inlet, and a sweep
// of 6 ms runs (averaged over their second half) on two threads into a fresh folder NAME.
Settings small_sweep_bed() {
  return load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml",
                    {"particles.placement=lattice", "particles.count=150",
                     "particles.fill_height=0.08", "inlet.kind=uniform"});
}
SweepOptions short_sweep(std::vector<double> velocities, const std::string& name) {
  SweepOptions o;
  o.velocities = std::move(velocities);
  o.run_time = 0.006;
  o.averaging_start = 0.003;
  o.threads = 2;
  o.out_dir = fluidbed::testing::temp_dir(name).string();
  return o;
}

}  // namespace

TEST(UmfFit, FindsTheKneeOfAPiecewiseCurve) {
  // dp = 2000 U below 1.8 m/s, 3600 Pa above, with a +-20 Pa wobble: U_mf = 1.8 m/s.
  std::vector<double> u, dp;
  for (double x : default_sweep_velocities()) {
    u.push_back(x);
    dp.push_back(std::min(2000.0 * x, 3600.0) + 20.0 * std::sin(7.0 * x));
  }
  const UmfFit f = fit_umf(u, dp);
  ASSERT_TRUE(f.ok) << f.why;
  EXPECT_NEAR(f.umf, 1.8, 0.02);
  EXPECT_NEAR(f.plateau, 3600.0, 15.0);
  EXPECT_NEAR(f.slope, 2000.0, 60.0);
  // A line with an offset and unsorted input: dp = 500 + 1500 U up to U = 2.0, then 3500.
  const UmfFit g = fit_umf({3.0, 0.5, 2.5, 1.0, 2.2, 1.5, 1.2, 2.8},
                           {3500, 1250, 3500, 2000, 3500, 2750, 2300, 3500});
  ASSERT_TRUE(g.ok);
  EXPECT_NEAR(g.umf, 2.0, 1e-9);
  EXPECT_FALSE(fit_umf({1.0, 2.0, 3.0}, {1, 2, 3}).ok);  // too few points
}

TEST(Sweep, BranchOrderAndStateHandOver) {
  Settings s = small_sweep_bed();
  SweepOptions o = short_sweep({1.5, 0.5, 1.0}, "sweep");  // any order in, sorted out
  const SweepResult r = run_sweep(s, o);
  ASSERT_EQ(r.up.size(), 3u);
  ASSERT_EQ(r.down.size(), 2u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(r.up[k].ok) << r.up[k].error;
    EXPECT_EQ(r.up[k].branch, "up");
    // Every increasing run starts from the same bed.
    EXPECT_EQ(r.up[k].start_hash, r.up[0].start_hash);
  }
  EXPECT_DOUBLE_EQ(r.up[0].u, 0.5);
  EXPECT_DOUBLE_EQ(r.up[2].u, 1.5);
  EXPECT_DOUBLE_EQ(r.down[1].u, 1.0);
  EXPECT_DOUBLE_EQ(r.down[0].u, 0.5);
  // Decreasing branch: 1.0 starts where 1.5 ended, 0.5 where 1.0 ended.
  EXPECT_EQ(r.down[1].start_hash, r.up[2].end_hash);
  EXPECT_EQ(r.down[0].start_hash, r.down[1].end_hash);
  EXPECT_NE(r.down[0].start_hash, r.up[0].start_hash);
  for (const auto& p : r.down) {
    EXPECT_TRUE(p.ok) << p.error;
    EXPECT_TRUE(std::filesystem::exists(p.state_path));
    EXPECT_GT(p.dp_mean, 0.0);
  }
  // Same sweep on one thread: the same numbers (each run is deterministic).
  o.threads = 1;
  o.out_dir = fluidbed::testing::temp_dir("sweep1").string();
  const SweepResult r1 = run_sweep(s, o);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(r1.up[k].dp_mean, r.up[k].dp_mean);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(r1.down[k].end_hash, r.down[k].end_hash);
}

TEST(Sweep, DecreasingOnlyRunsTheTopThenTheFullSweepsChain) {
  // What U_mf needs alone (SweepOptions::decreasing_only): the top velocity from the scene's
  // start, then the chain down from it, the same runs to the bit as the full sweep's; the
  // increasing runs below the top are not run, and say so.
  const Settings s = small_sweep_bed();
  SweepOptions o = short_sweep({0.5, 1.0, 1.5}, "sweep_full");
  const SweepResult full = run_sweep(s, o);
  o.decreasing_only = true;
  o.out_dir = fluidbed::testing::temp_dir("sweep_down").string();
  const SweepResult down = run_sweep(s, o);
  ASSERT_EQ(down.up.size(), 3u);
  ASSERT_TRUE(down.up[2].ok) << down.up[2].error;
  EXPECT_EQ(down.up[2].end_hash, full.up[2].end_hash);
  EXPECT_EQ(down.up[2].dp_mean, full.up[2].dp_mean);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_FALSE(down.up[k].ok);
    EXPECT_EQ(down.up[k].error, "not run: decreasing branch only");
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(o.out_dir) / "runs" /
                                         (k == 0 ? "up-0.500" : "up-1.000")));
    ASSERT_TRUE(down.down[k].ok) << down.down[k].error;
    EXPECT_EQ(down.down[k].start_hash, full.down[k].start_hash);
    EXPECT_EQ(down.down[k].end_hash, full.down[k].end_hash);
    EXPECT_EQ(down.down[k].dp_mean, full.down[k].dp_mean);
  }
  // A sweep of one kind is not resumed as the other.
  o.resume = true;
  o.decreasing_only = false;
  EXPECT_THROW(check_sweep_resume(s, o), InputError);
}

TEST(Sweep, VelocitiesThatWouldShareARunFolderAreRefused) {
  // Runs are kept in runs/up-1.800 and the like: 1.8001 and 1.8004 m/s would share a folder.
  Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml",
                          {"particles.placement=lattice", "particles.count=150"});
  SweepOptions o;
  o.velocities = {2.0, 1.8004, 1.8001};
  o.run_time = 0.006;
  o.averaging_start = 0.003;
  o.out_dir = fluidbed::testing::temp_dir("sweep-close").string();
  try {
    run_sweep(s, o);
    FAIL() << "velocities 1 mm/s apart were accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("1.8001 and 1.8004"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  // Nothing was run or written for the refused sweep.
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(o.out_dir) / "runs"));
  // From the command line, into a folder holding a finished sweep: refused before the folder is
  // touched (its summary.json stays), one line, status 2; the same with --seeds.
  const std::filesystem::path done = fluidbed::testing::temp_dir("sweep-close-done");
  fluidbed::testing::write_file(done / "summary.json", "{\"umf_m_s\": 1.8}\n");
  for (const char* seeds : {"", " --seeds 2"}) {
    const fluidbed::testing::CommandResult c = fluidbed::testing::run_fluidbed(
        "sweep " + std::string(FLUIDBED_ASSET_DIR) +
            "/scenes/xu_yu_1997.toml --velocities 2.0,1.8004,1.8001 --out " + done.string() + seeds,
        "sweep-close-cli");
    EXPECT_EQ(c.status, 2) << c.err;
    EXPECT_NE(c.err.find("1 mm/s"), std::string::npos) << c.err;
    EXPECT_EQ(std::count(c.err.begin(), c.err.end(), '\n'), 1) << c.err;
    EXPECT_EQ(fluidbed::testing::read_file(done / "summary.json"), "{\"umf_m_s\": 1.8}\n");
  }
}

TEST(Sweep, DecreasingBranchStartsFromTheHighestFinishedRun) {
  // At 1000 and 1200 m/s the first gas step's CFL number is far above 1: both runs fail. The
  // decreasing branch then starts from 1.5 m/s, the highest run that finished.
  Settings s = small_sweep_bed();
  SweepOptions o = short_sweep({0.5, 1.0, 1.5, 1000.0, 1200.0}, "sweep-fail");
  const SweepResult r = run_sweep(s, o);
  ASSERT_EQ(r.up.size(), 5u);
  ASSERT_EQ(r.down.size(), 4u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_TRUE(r.up[k].ok) << r.up[k].error;
  for (std::size_t k = 3; k < 5; ++k) {
    EXPECT_FALSE(r.up[k].ok);
    EXPECT_NE(r.up[k].error.find("CFL"), std::string::npos) << r.up[k].error;
  }
  EXPECT_TRUE(r.down[1].ok) << r.down[1].error;
  EXPECT_TRUE(r.down[0].ok) << r.down[0].error;
  EXPECT_EQ(r.down[1].start_hash, r.up[2].end_hash);  // 1.0 from where 1.5 ended
  EXPECT_EQ(r.down[0].start_hash, r.down[1].end_hash);
  for (std::size_t k = 2; k < 4; ++k) {
    EXPECT_FALSE(r.down[k].ok);
    EXPECT_EQ(r.down[k].error.rfind("not run", 0), 0u) << r.down[k].error;
  }

  // The command line: sweep.csv has every run, the failed ones with their reason.
  const auto dir = fluidbed::testing::temp_dir("sweep-fail-cli");
  const auto c = fluidbed::testing::run_fluidbed(
      "sweep " + std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml --velocities 0.5,1.0,1000 "
      "--run-time 0.006 --averaging-start 0.003 --set particles.placement=lattice "
      "--set particles.count=150 --set particles.fill_height=0.08 --set inlet.kind=uniform --out " +
          dir.string(),
      "sweep-fail-cli");
  ASSERT_EQ(c.status, 0) << c.err;
  const std::string csv = fluidbed::testing::read_file(dir / "sweep.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "branch,u_superficial,dp_mean,dp_std,status,wall_time_s,failure");
  EXPECT_NE(csv.find("up,1000.0000,0,0,failed,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("CFL"), std::string::npos) << csv;
  EXPECT_NE(csv.find("down,0.5000,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",not_run,"), std::string::npos) << csv;
}

TEST(Sweep, DefaultVelocitiesFollowTheScenesParticles) {
  // The paper's bed: the paper's 23 velocities exactly.
  const Settings paper = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml");
  EXPECT_EQ(default_sweep_velocities(paper), default_sweep_velocities());
  // 4 mm glass in air: the terminal velocity by hand. At u = 16 m/s, Re = 1.205 16 0.004 / 1.8e-5
  // = 4285, C_d = (0.63 + 4.8 / 65.46)^2 = 0.4950, drag 0.4950 x 0.5 x 1.205 x 256 x 1.2566e-5 N
  // = 9.59e-4 N against the weight less buoyancy 8.876e-4 N: u_t a little below 16 m/s.
  const double ut = terminal_velocity(paper);
  EXPECT_GT(ut, 14.5);
  EXPECT_LT(ut, 16.0);
  // Lighter particles (1350 kg/m^3): Wen-Yu's U_mf falls (Ar halves), and the list with it.
  Settings light = paper;
  light.particles.density = 1350.0;
  const auto v = default_sweep_velocities(light);
  const double umf_ratio = wen_yu_umf(0.004, 1350.0, 1.205, 1.8e-5, 9.81) /
                           wen_yu_umf(0.004, 2700.0, 1.205, 1.8e-5, 9.81);
  ASSERT_EQ(v.size(), 23u);
  EXPECT_NEAR(v.back(), 3.2 * umf_ratio, 0.006);
  EXPECT_NEAR(v.front(), 0.5 * umf_ratio, 0.006);
  // The top of the list (1.8 U_mf) stays far below the terminal velocity: for spheres u_t / U_mf
  // is 8 or more by these correlations, so the 0.8 u_t cap only guards.
  EXPECT_LT(v.back(), 0.25 * terminal_velocity(light));
  EXPECT_LT(default_sweep_velocities(paper).back(), 0.25 * ut);
}
