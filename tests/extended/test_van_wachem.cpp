// The bubbling bed of van Wachem et al. (2001), five particles deep (assets/scenes/
// van_wachem_2001.toml): 12 s from its packed bed through the command line, as a user runs it and
// as the peer (Lethe) measures it: the pressure at the experiment's point (centre line, 45 mm up)
// against the outlet, the highest particle, statistics from 2 s. The experiment's figures are
// printed beside ours. The regime (bubbling) and a regular cycle at the probe are what the
// experiment shows: since the gas enters through the peer's plenum, both packings measured
// (docs/second-bed.md) bubble with a regular cycle, and so must this run. The frequency
// (2.9 Hz against 2.3 to 2.4) is reported, not asserted: it is not reproduced yet (issue 35).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../test_support.hpp"

using namespace fluidbed::testing;

TEST(VanWachem, TwelveSecondsAtThePeersSettingsBubbleWithARegularCycle) {
  const auto dir = temp_dir("van-wachem");
  const CommandResult r = run_fluidbed(
      "run " + std::string(FLUIDBED_ASSET_DIR) + "/scenes/van_wachem_2001.toml --threads 2 " +
          "--bubbles --out " + (dir / "run").string(),
      "van-wachem");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(read_file(dir / "run" / "summary.json"));
  ASSERT_EQ(j["status"], "completed");
  EXPECT_DOUBLE_EQ(j["sim_time_s"].get<double>(), 12.0);
  ASSERT_TRUE(j.contains("probes") && j["probes"].size() == 1u);
  const auto& probe = j["probes"][0];
  const double dp = j["dp_mean_pa"], weight = j["bed_weight_per_area_pa"];
  std::printf("probe at (%.3f, %.3f) m: std %.1f Pa (experiment 82 Pa), spectrum peak %.2f Hz "
              "(experiment 2.3 to 2.4 Hz), %s\n",
              probe["point_m"][0].get<double>(), probe["point_m"][1].get<double>(),
              probe["std_pa"].get<double>(), probe["peak_hz"].get<double>(),
              probe["cycle"].get<std::string>().c_str());
  std::printf("bed top %.4f to %.4f m, mean %.4f m (experiment 0.094 to 0.149 m); regime %s, "
              "%.1f bubbles formed per s; dp %.1f Pa (W/A %.1f Pa); %.0f wall s per simulated s\n",
              j["bed_top_min_m"].get<double>(), j["bed_top_max_m"].get<double>(),
              j["bed_top_mean_m"].get<double>(), j["bubbles"]["regime"].get<std::string>().c_str(),
              j["bubbles"]["formed_per_s"].get<double>(), dp, weight,
              j["wall_s_per_sim_s"].get<double>());
  const double sd = probe["std_pa"].get<double>();
  EXPECT_TRUE(std::isfinite(sd) && sd > 0.0) << sd;
  // A fluidized bed carries its weight: the mean pressure drop over the bed is W/A less what the
  // walls hold by friction (a thick slab's front and back walls touch every sphere near them) and
  // what rests on the floor where the gas, free to spread under it, leaves the bed still (the
  // packings measured: 12.5 % below W/A, both). 15 %: that and one run's spread.
  EXPECT_NEAR(dp, weight, 0.15 * weight);
  // The experiment's regime and a regular cycle at its pressure point (bubbles passing).
  EXPECT_EQ(j["bubbles"]["regime"], "bubbling");
  EXPECT_EQ(probe["cycle"], "regular cycle");
  // Risen above the packed bed (0.081 m) and inside the column.
  EXPECT_GT(j["bed_top_min_m"].get<double>(), 0.081);
  EXPECT_LT(j["bed_top_max_m"].get<double>(), 0.5);
  // The timeseries carries the probe at every row.
  std::ifstream csv(dir / "run" / "timeseries.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",p_probe_1"), std::string::npos) << header;
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 12000);
}
