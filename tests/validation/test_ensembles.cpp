// Ensembles over packings (`--seeds`, run/ensemble.hpp): each seed its own packing, the same seed
// the same bits, the first seed the run without --seeds, and the ensemble's summary the mean and
// spread of the members' summaries. Small beds (600 particles, the teaching scene's cheap contact
// and gas settings), short runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "run/ensemble.hpp"

using namespace fluidbed;
using fluidbed::testing::read_file;
using fluidbed::testing::run_fluidbed;
using fluidbed::testing::temp_dir;
using fluidbed::testing::TerminatedRun;
using fluidbed::testing::fluidbed_terminated;

namespace {

// The paper's bed 5 cm wide (5 gas cells across) with 600 particles packed for 0.5 s from a
// lattice 0.3 m high (a bed about 17 cm high, so that the solid fraction's band, 2 cm to 3 cm
// below the top, holds many rows), at cheap contact, step and gas settings (the teaching scene's
// earlier ones: 10,000 N/m, 6.708e-5 s, the gas every 2 steps to 1e-3), averaging from 0.05 s.
std::string small_bed_args() {
  return "run " + std::string(FLUIDBED_ASSET_DIR) +
         "/scenes/xu_yu_1997.toml --set particles.count=600 --set domain.width=0.05 "
         "--set gas.cells_x=5 --set particles.fill_height=0.3 "
         "--set particles.packing_time=0.5 --set contact.stiffness=10000 "
         "--set contact.damping=0.06708 --set time.dt=6.708e-5 "
         "--set coupling.particle_steps_per_gas_step=2 --set gas.tolerance=1e-3 "
         "--set gas.preconditioner_refresh=0.1 --set diagnostics.averaging_start=0.05 "
         "--set 'diagnostics.probes=[]'";  // the scene's probe is outside this narrow bed
}

nlohmann::json read_json(const std::filesystem::path& p) {
  const std::string text = read_file(p);
  EXPECT_FALSE(text.empty()) << p;
  return text.empty() ? nlohmann::json::object() : nlohmann::json::parse(text);
}

}  // namespace

TEST(Ensembles, BadSeedsAreOneLineAndStatus2) {
  const auto dir = temp_dir("ensemble-bad");
  const std::string scene = std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml";
  for (const std::string seeds : {"0", "1,1", "2.5", "abc", "3,x", "-1", "4,"}) {
    for (const std::string verb : {"run", "sweep"}) {
      const auto r =
          run_fluidbed(verb + " " + scene + " --seeds=" + seeds + " --out " + (dir / "x").string(),
                       "ensemble-bad");
      EXPECT_EQ(r.status, 2) << verb << " --seeds " << seeds << ": " << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_NE(r.err.find("seed"), std::string::npos) << r.err;
    }
  }
  // A start no seed changes (one dropped particle), and options that cannot work per seed.
  const auto drop = run_fluidbed("run " + std::string(FLUIDBED_ASSET_DIR) +
                                     "/scenes/drop.toml --seeds 2 --out " + (dir / "d").string(),
                                 "ensemble-drop");
  EXPECT_EQ(drop.status, 2) << drop.err;
  EXPECT_NE(drop.err.find("placement"), std::string::npos) << drop.err;
  for (const std::string& opt :
       std::vector<std::string>{"--frames", "--resume " + (dir / "d").string()}) {
    const auto r = run_fluidbed(
        "run " + scene + " --seeds 2 " + opt + " --out " + (dir / "f").string(), "ensemble-opt");
    EXPECT_EQ(r.status, 2) << opt << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(Ensembles, SeedListsAndStatistics) {
  EXPECT_EQ(parse_seeds("3", 5), (std::vector<std::uint64_t>{5, 6, 7}));
  EXPECT_EQ(parse_seeds("1", 9), (std::vector<std::uint64_t>{9}));
  EXPECT_EQ(parse_seeds("3,7,11", 5), (std::vector<std::uint64_t>{3, 7, 11}));
  EXPECT_THROW(parse_seeds("0", 1), InputError);
  EXPECT_THROW(parse_seeds("7,7", 1), InputError);
  EXPECT_THROW(parse_seeds("", 1), InputError);
  // By hand: 1, 2, 6 has mean 3 and sample variance (4 + 1 + 9) / 2 = 7.
  const nlohmann::json e =
      ensemble_statistics({{{"a", 1.0}, {"b", {{"c", 10}}}, {"s", "x"}, {"t", true}},
                           {{"a", 2.0}, {"b", {{"c", nullptr}}}},
                           {{"a", 6.0}, {"b", {{"c", 20}}}}});
  EXPECT_DOUBLE_EQ(e["a"]["mean"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(e["a"]["std"].get<double>(), std::sqrt(7.0));
  EXPECT_EQ(e["a"]["min"].get<double>(), 1.0);
  EXPECT_EQ(e["a"]["max"].get<double>(), 6.0);
  EXPECT_EQ(e["a"]["n"].get<int>(), 3);
  EXPECT_EQ(e["b.c"]["n"].get<int>(), 2);  // the null is not a sample
  EXPECT_DOUBLE_EQ(e["b.c"]["mean"].get<double>(), 15.0);
  EXPECT_FALSE(e.contains("s"));
  EXPECT_FALSE(e.contains("t"));
  EXPECT_TRUE(ensemble_statistics({{{"a", 4.0}}})["a"]["std"].is_null());  // one seed: no spread
}

TEST(Ensembles, EachSeedItsOwnPackingAndTheSameSeedTheSameBits) {
  const auto dir = temp_dir("ensemble-packings");
  // Two packings, side by side.
  const auto r = run_fluidbed(
      small_bed_args() + " --seeds 2 --until 0 --out " + (dir / "e").string(), "ensemble-packings");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json top = read_json(dir / "e" / "summary.json");
  ASSERT_EQ(top["seeds"], nlohmann::json({1, 2})) << top.dump();
  const nlohmann::json a = read_json(dir / "e" / "seeds" / "1" / "summary.json");
  const nlohmann::json b = read_json(dir / "e" / "seeds" / "2" / "summary.json");
  EXPECT_NE(a["state_hash"], b["state_hash"]);
  EXPECT_EQ(top["state_hashes"]["1"], a["state_hash"]);
  const double ha = a["bed_height_m"].get<double>(), hb = b["bed_height_m"].get<double>();
  const double fa = a["solid_fraction"].get<double>(), fb = b["solid_fraction"].get<double>();
  EXPECT_LT(std::abs(ha - hb), 0.02 * ha) << ha << " " << hb;
  EXPECT_LT(std::abs(fa - fb), 0.02 * fa) << fa << " " << fb;
  // The first seed is the scene's own: the run without --seeds, bit for bit.
  const auto plain = run_fluidbed(small_bed_args() + " --until 0 --out " + (dir / "plain").string(),
                                  "ensemble-plain");
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(read_json(dir / "plain" / "summary.json")["state_hash"], a["state_hash"]);
  // The same seed packed again from nothing (a fresh cache) gives the same bits.
  const auto cache = dir / "cache";
  std::filesystem::create_directories(cache);
  ::setenv("FLUIDBED_CACHE", cache.c_str(), 1);
  const auto again =
      run_fluidbed(small_bed_args() + " --seeds 2,5 --until 0 --out " + (dir / "again").string(),
                   "ensemble-again");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(read_json(dir / "again" / "seeds" / "2" / "summary.json")["state_hash"],
            b["state_hash"]);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(cache),
                          std::filesystem::directory_iterator()),
            2);  // one cached packing per seed
}

TEST(Ensembles, SummaryHoldsTheMeanAndSpreadOfTheSeeds) {
  const auto dir = temp_dir("ensemble-stats");
  const auto r = run_fluidbed(
      small_bed_args() + " --seeds 3 --until 0.1 --plots --out " + dir.string(), "ensemble-stats");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json top = read_json(dir / "summary.json");
  const nlohmann::json& e = top["ensemble"];
  std::map<std::string, std::vector<double>> values;
  for (int seed = 1; seed <= 3; ++seed) {
    std::map<std::string, double> flat;
    flatten_numbers(read_json(dir / "seeds" / std::to_string(seed) / "summary.json"), "", flat);
    for (const auto& [k, v] : flat) values[k].push_back(v);
  }
  for (const char* key : {"dp_mean_pa", "bed_height_m", "solid_fraction", "bed_height_mean_m",
                          "dp_spectrum.dominant_frequency_hz", "max_overlap_ratio"})
    EXPECT_TRUE(e.contains(key)) << key;
  ASSERT_EQ(e.size(), values.size());
  for (const auto& [key, v] : values) {
    ASSERT_TRUE(e.contains(key)) << key;
    double mean = 0.0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    double var = 0.0;
    for (double x : v)
      var += (x - mean) * (x - mean) / static_cast<double>(std::max<std::size_t>(v.size(), 2) - 1);
    const double tol = 1e-12 * std::max(1.0, std::abs(mean));
    EXPECT_EQ(e[key]["n"].get<std::size_t>(), v.size()) << key;
    EXPECT_NEAR(e[key]["mean"].get<double>(), mean, tol) << key;
    if (v.size() == 1)  // a value only one seed measured: no spread
      EXPECT_TRUE(e[key]["std"].is_null()) << key;
    else
      EXPECT_NEAR(e[key]["std"].get<double>(), std::sqrt(var), 1e-9 * std::max(1.0, std::sqrt(var)))
          << key;
    EXPECT_EQ(e[key]["min"].get<double>(), *std::min_element(v.begin(), v.end())) << key;
    EXPECT_EQ(e[key]["max"].get<double>(), *std::max_element(v.begin(), v.end())) << key;
  }
  // The top summary's plain numbers are the means; the packings differ, so dp does.
  EXPECT_EQ(top["dp_mean_pa"], e["dp_mean_pa"]["mean"]);
  EXPECT_GT(e["dp_mean_pa"]["std"].get<double>(), 0.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "dp.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "seeds" / "2" / "timeseries.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "seeds" / "3" / "dp.png"));
}

TEST(Ensembles, SweepOverSeeds) {
  const auto dir = temp_dir("ensemble-sweep");
  const auto r = run_fluidbed(
      "sweep " + std::string(FLUIDBED_ASSET_DIR) +
          "/scenes/xu_yu_1997.toml --velocities 0.5,1.0,1.5 --run-time 0.006 "
          "--averaging-start 0.003 --set particles.placement=lattice --set particles.count=150 "
          "--set particles.fill_height=0.08 --set inlet.kind=uniform --seeds 4,9 --out " +
          dir.string(),
      "ensemble-sweep");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json top = read_json(dir / "summary.json");
  EXPECT_EQ(top["seeds"], nlohmann::json({4, 9}));
  const nlohmann::json a = read_json(dir / "seeds" / "4" / "summary.json");
  const nlohmann::json b = read_json(dir / "seeds" / "9" / "summary.json");
  // Different lattice starts: different dp at the lowest velocity.
  EXPECT_NE(a["points"][0]["dp_mean"], b["points"][0]["dp_mean"]);
  EXPECT_EQ(top["ensemble"]["wall_time_s"]["n"].get<int>(), 2);
  EXPECT_DOUBLE_EQ(top["ensemble"]["bed_weight_per_area_pa"]["mean"].get<double>(),
                   a["bed_weight_per_area_pa"].get<double>());
  const std::string csv = read_file(dir / "sweep.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "branch,u_superficial,dp_mean,dp_std_over_seeds,dp_min,dp_max,seeds_ok");
  EXPECT_NE(csv.find("up,0.5000,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("down,1.0000,"), std::string::npos) << csv;
  EXPECT_TRUE(std::filesystem::exists(dir / "sweep.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "seeds" / "9" / "sweep.csv"));
}

// `run --seeds` stopped and resumed (each member's checkpoint, DIR/ensemble.json): run one member
// a time (--threads 2 on two cores), stopped by SIGTERM in the second member, so that the first
// has finished, the second holds a checkpoint and the third has not begun. `run --resume DIR`
// gives the unstopped ensemble's files: the same timeseries of every member, the same summary but
// for the wall-time figures.
TEST(Ensembles, StoppedEnsembleResumesToTheUnstoppedOnesFiles) {
  namespace fs = std::filesystem;
  const fs::path dir = temp_dir("ensemble-resume");
  // 1.2 s: the second member is stopped past 0.5 s (50 rows), with 0.7 s left to stop it in.
  const std::string args = small_bed_args() + " --seeds 3 --until 1.2 --threads 2 --plots";
  const auto ref = run_fluidbed(args + " --out " + (dir / "ref").string(), "ensemble-resume-ref");
  ASSERT_EQ(ref.status, 0) << ref.err;

  const fs::path stop = dir / "stop";
  fs::create_directories(stop);
  const fs::path second = stop / "seeds" / "2" / "timeseries.csv";
  const TerminatedRun t = fluidbed_terminated(args + " --out " + stop.string(), stop, [&] {
    const std::string rows = read_file(second);
    return std::count(rows.begin(), rows.end(), '\n') > 50;
  });
  ASSERT_TRUE(t.terminated) << "the ensemble ended before the second member had 50 rows";
  ASSERT_EQ(t.status, 130) << read_file(stop / "err.txt");
  EXPECT_TRUE(fs::exists(stop / "seeds" / "1" / "summary.json"));
  EXPECT_TRUE(fs::exists(stop / "seeds" / "2" / "checkpoint"));
  EXPECT_FALSE(fs::exists(stop / "seeds" / "3"));
  EXPECT_FALSE(fs::exists(stop / "summary.json"));
  EXPECT_NE(read_file(stop / "err.txt").find("fluidbed run --resume " + stop.string()),
            std::string::npos);

  // A member alone, or the ensemble with another end time: one line, status 2.
  for (const std::string& bad : {"run --resume " + (stop / "seeds" / "2").string(),
                                 "run --resume " + stop.string() + " --until 3"}) {
    const auto r = run_fluidbed(bad, "ensemble-resume-bad");
    EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }

  const auto resumed = run_fluidbed("run --resume " + stop.string(), "ensemble-resume-end");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("seed 1: finished before"), std::string::npos) << resumed.out;
  EXPECT_NE(resumed.out.find("seed 2: resumed at t = "), std::string::npos) << resumed.out;
  for (const char* seed : {"1", "2", "3"}) {
    EXPECT_EQ(read_file(dir / "ref" / "seeds" / seed / "timeseries.csv"),
              read_file(stop / "seeds" / seed / "timeseries.csv"))
        << seed;
    EXPECT_FALSE(fs::exists(stop / "seeds" / seed / "checkpoint")) << seed;
    EXPECT_TRUE(fs::exists(stop / "seeds" / seed / "trajectory.png")) << seed;
  }
  std::map<std::string, double> a, b;
  flatten_numbers(read_json(dir / "ref" / "summary.json"), "", a);
  flatten_numbers(read_json(stop / "summary.json"), "", b);
  ASSERT_EQ(a.size(), b.size());
  int compared = 0;
  for (const auto& [key, value] : a) {
    if (key.find("wall") != std::string::npos || key.find("particle_steps_per_s") != std::string::npos)
      continue;
    ASSERT_TRUE(b.count(key)) << key;
    EXPECT_EQ(value, b[key]) << key;
    ++compared;
  }
  EXPECT_GT(compared, 100);
  EXPECT_TRUE(fs::exists(stop / "dp.png"));
}
