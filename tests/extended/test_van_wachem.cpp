// The bubbling bed of van Wachem et al. (2001), five particles deep (assets/scenes/
// van_wachem_2001.toml): 6 s from its packed bed through the command line, as a user runs it.
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

TEST(VanWachem, BubblingThickBedRunsSixSecondsAroundItsWeight) {
  const auto dir = temp_dir("van-wachem");
  const CommandResult r = run_fluidbed(
      "run " + std::string(FLUIDBED_ASSET_DIR) + "/scenes/van_wachem_2001.toml --out " +
          (dir / "run").string(),
      "van-wachem");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(read_file(dir / "run" / "summary.json"));
  ASSERT_EQ(j["status"], "completed");
  EXPECT_DOUBLE_EQ(j["sim_time_s"].get<double>(), 6.0);
  for (const char* key : {"dp_mean_pa", "bed_weight_per_area_pa", "bed_height_mean_m"})
    ASSERT_TRUE(j.contains(key) && j[key].is_number()) << key;
  const double dp = j["dp_mean_pa"], weight = j["bed_weight_per_area_pa"];
  const double height = j["bed_height_mean_m"];
  std::printf("dp mean %.1f Pa (bed weight per area %.1f Pa), bed height mean %.4f m, "
              "largest overlap after start-up %.4f, %.0f wall s per simulated s\n",
              dp, weight, height, j["max_overlap_ratio_after_startup"].get<double>(),
              j["wall_s_per_sim_s"].get<double>());
  // A bubbling bed carries its weight: the mean pressure drop over the bed is W/A less what the
  // four walls hold by friction (a thick slab's front and back walls touch every sphere near
  // them). 15 %: the spread of one run's mean (one sample of a chaotic bed) and the walls.
  EXPECT_NEAR(dp, weight, 0.15 * weight);
  // Expanded above the packed bed (0.081 m) and below the column's top.
  EXPECT_GT(height, 0.081);
  EXPECT_LT(height, 0.5);
  // The timeseries carries the bed height at every row.
  std::ifstream csv(dir / "run" / "timeseries.csv");
  std::string header;
  std::getline(csv, header);
  const std::vector<std::string> columns = split_csv_line(header);
  std::size_t col = columns.size();
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == "bed_height") col = k;
  ASSERT_LT(col, columns.size()) << header;
  int rows = 0;
  for (std::string line; std::getline(csv, line);) {
    const double h = std::stod(split_csv_line(line).at(col));
    EXPECT_GT(h, 0.05) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 6000);
}
