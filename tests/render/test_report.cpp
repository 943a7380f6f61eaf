// The report of `fluidbed reproduce` (app/cli/paper_report.hpp): the second bed's section, from
// made-up run summaries whose spreads and verdicts are worked out by hand below.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/paper_report.hpp"

using fluidbed::app::second_bed_section;

namespace {

// A van Wachem run's summary with the figures the section reads.
nlohmann::json summary(double peak, double std_pa, const char* cycle, double top_min,
                       double top_max, const char* regime) {
  return {{"sim_time_s", 12.0},
          {"averaging_start_s", 2.0},
          {"bed_weight_per_area_pa", 531.4},
          {"dp_mean_pa", 464.7},
          {"bed_top_min_m", top_min},
          {"bed_top_max_m", top_max},
          {"probes", {{{"peak_hz", peak}, {"std_pa", std_pa}, {"cycle", cycle}}}},
          {"bubbles",
           {{"regime", regime},
            {"slugging_fraction", 0.13},
            {"formed_per_s", 12.8},
            {"mean_d_eq_m", 0.0236}}}};
}

// The table row that starts with `what`, whole.
std::string row(const std::string& md, const std::string& what) {
  const auto at = md.find("| " + what + " |");
  if (at == std::string::npos) return "";
  return md.substr(at, md.find('\n', at) - at);
}

}  // namespace

TEST(Report, SecondBedSectionGivesEachPackingTheSpreadAndTheVerdict) {
  const std::vector<nlohmann::json> runs = {
      summary(2.86, 86.1, "regular cycle", 0.0944, 0.1534, "bubbling"),
      summary(2.83, 86.3, "regular cycle", 0.0940, 0.1480, "bubbling")};
  const std::string md = second_bed_section(runs, {1, 2});
  EXPECT_NE(md.find("## The second bed: van Wachem et al. (2001)"), std::string::npos);
  EXPECT_NE(md.find("2 packings (lattice seeds 1, 2), 12 s with statistics from 2 s"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("resolution is 0.25 Hz (Welch, 4 s segments)"), std::string::npos) << md;
  // Peak: mean 2.845, std 0.0212; mean + 2 std = 2.887 stays above 2.4.
  const std::string peak = row(md, "probe (0.045, 0.045) m, spectrum peak (Hz)");
  EXPECT_NE(peak.find("| 2.86, 2.83 (2.84 +- 0.02) | outside 2 std |"), std::string::npos) << peak;
  // Standard deviation: 86.2 +- 0.14, so 82 is outside.
  EXPECT_NE(row(md, "probe, standard deviation (Pa)").find("86.1, 86.3 (86.2 +- 0.1) | outside"),
            std::string::npos)
      << md;
  // Lowest top: 0.0942 +- 0.00028: 0.094 lies within; highest: 0.1507 +- 0.0038: 0.149 within.
  EXPECT_NE(row(md, "highest particle, lowest (m)").find("within 2 std"), std::string::npos) << md;
  EXPECT_NE(row(md, "highest particle, highest (m)").find("0.153, 0.148 (0.151 +- 0.004) | within"),
            std::string::npos)
      << md;
  EXPECT_NE(row(md, "probe, cycle").find("regular cycle; regular cycle"), std::string::npos) << md;
  EXPECT_NE(row(md, "regime (bubble tracker)").find("bubbling (slug in 13 % of frames), bubbling"),
            std::string::npos)
      << md;
  EXPECT_NE(row(md, "mean dp (Pa)").find("531 (W/A"), std::string::npos) << md;
  EXPECT_NE(md.find("(second_bed/seeds/2/montage.png)"), std::string::npos);

  // One packing: no spread to judge by, and the section says so.
  const std::string one = second_bed_section({runs.front()}, {1});
  EXPECT_NE(row(one, "probe, standard deviation (Pa)").find("one packing: spread not measured"),
            std::string::npos)
      << one;
  // --quick: no runs, and how to make them.
  const std::string none = second_bed_section({}, {});
  EXPECT_NE(none.find("Not run: `--quick` leaves it out."), std::string::npos) << none;
  EXPECT_NE(none.find("fluidbed run assets/scenes/van_wachem_2001.toml"), std::string::npos);
  EXPECT_EQ(none.find("| figure |"), std::string::npos);
}
