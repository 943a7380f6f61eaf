// `fluidbed study sensitivity --scene SCENE --vary ...`: on a tiny bed (300 spheres, 0.2 s a
// run), every varied key reaches its run and nothing else changes (the resolved scene of each
// point against the base's), what varying the step would move is held, the table, runs, charts
// and summary are written, a resume reads the points back, and bad input is one line, status 2.
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include "../test_support.hpp"

using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

// The paper's bed made small (the studies' tiny size): seconds a run.
const std::string kTinyBed =
    "--scene \"" + std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml\"" +
    " --set domain.width=0.06 --set domain.height=0.3 --set particles.count=300"
    " --set particles.fill_height=0.12 --set particles.packing_time=0.3 --set gas.cells_x=6"
    " --set gas.cells_y=15 --set diagnostics.averaging_start=0.05"
    " --set 'diagnostics.probes=[[0.03, 0.05]]' --until 0.2";

// The "section.key" of every line where two resolved scenes differ.
std::set<std::string> differing_keys(const std::string& a, const std::string& b) {
  std::istringstream ia(a), ib(b);
  std::string la, lb, section;
  std::set<std::string> keys;
  while (std::getline(ia, la) && std::getline(ib, lb)) {
    if (!la.empty() && la[0] == '[') section = la.substr(1, la.find(']') - 1);
    if (la == lb || la.empty() || la[0] == '#') continue;
    keys.insert(section + "." + la.substr(0, la.find(" = ")));
  }
  return keys;
}

std::vector<std::vector<std::string>> csv_rows(const fs::path& p) {
  std::istringstream in(read_file(p));
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(split_csv_line(line));
  return rows;
}

}  // namespace

TEST(SensitivityStudy, EachVariedKeyReachesItsRunAndNothingElseChanges) {
  const fs::path dir = temp_dir("study-sensitivity");
  const std::string args = "study sensitivity " + kTinyBed +
                           " --vary gas.cells_x,gas.cells_y=4:10 --vary "
                           "inlet.superficial_velocity=3.5 --vary time.dt=7.5e-6 --out \"" +
                           dir.string() + "\"";
  const CommandResult r = run_fluidbed(args, "study-sensitivity");
  ASSERT_EQ(r.status, 0) << r.err << r.out;

  // Point k's resolved scene differs from the base's in exactly its keys; the step's point also
  // in the particle steps per gas step, which hold the gas step (1.5e-5 s) in seconds.
  const std::string base = read_file(dir / "scenes" / "00.toml");
  const std::vector<std::set<std::string>> expected = {
      {"gas.cells_x", "gas.cells_y"},
      {"inlet.superficial_velocity"},
      {"time.dt", "coupling.particle_steps_per_gas_step"}};
  for (std::size_t k = 0; k < expected.size(); ++k) {
    char name[32];  // (not "0" + std::to_string: GCC 12 warns of a memcpy overlap it imagines)
    std::snprintf(name, sizeof name, "%02zu.toml", k + 1);
    const fs::path scene = dir / "scenes" / name;
    const std::string text = read_file(scene);
    EXPECT_EQ(differing_keys(text, base), expected[k]) << scene;
  }
  EXPECT_NE(read_file(dir / "scenes" / "03.toml").find("particle_steps_per_gas_step = 2"),
            std::string::npos);

  // The table: the base and a row a varied value, each measured (one packing: n = 1).
  const auto table = csv_rows(dir / "study.csv");
  ASSERT_EQ(table.size(), 5u);  // the header and 4 points
  const auto& head = table[0];
  const auto col = [&](const char* name) {
    return static_cast<std::size_t>(std::find(head.begin(), head.end(), name) - head.begin());
  };
  for (const char* c : {"point", "held", "regime", "probe_1_std_pa", "probe_1_peak_hz",
                        "bed_top_max_m", "dp_std_pa", "bubbles_formed_per_s",
                        "cost_cpu_s_per_sim_s", "moves"})
    ASSERT_LT(col(c), head.size()) << c;
  EXPECT_EQ(table[1][col("point")], "base");
  EXPECT_EQ(table[2][col("point")], "gas.cells_x,gas.cells_y=4:10");
  EXPECT_NE(table[4][col("held")].find("gas step held at 1.5e-05 s"), std::string::npos);
  for (std::size_t k = 1; k < table.size(); ++k) {
    EXPECT_FALSE(table[k][col("probe_1_std_pa")].empty()) << table[k][0];
    EXPECT_FALSE(table[k][col("regime")].empty()) << table[k][0];
  }
  // A faster gas lifts the bed's top (3.5 m/s against the scene's 2.8 m/s).
  EXPECT_GT(std::stod(table[3][col("bed_top_max_m")]), std::stod(table[1][col("bed_top_max_m")]));
  EXPECT_EQ(csv_rows(dir / "runs.csv").size(), 5u);
  for (const char* f : {"vary-gas_cells_x-gas_cells_y.png", "vary-inlet_superficial_velocity.png",
                        "vary-time_dt.png", "summary.md"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const std::string summary = read_file(dir / "summary.md");
  EXPECT_NE(summary.find("Which keys move which figures"), std::string::npos);
  EXPECT_NE(summary.find("One packing a point"), std::string::npos);

  // Resumed as it was started (--out DIR --resume alone): every point read back, the same table.
  const std::string before = read_file(dir / "study.csv");
  const CommandResult again =
      run_fluidbed("study sensitivity --out \"" + dir.string() + "\" --resume", "study-sens-resume");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(read_file(dir / "study.csv"), before);
  // Resumed with another variation: refused in one line, nothing touched.
  const CommandResult other = run_fluidbed(
      "study sensitivity " + kTinyBed + " --vary inlet.superficial_velocity=3 --out \"" +
          dir.string() + "\" --resume",
      "study-sens-other");
  EXPECT_EQ(other.status, 2);
  EXPECT_EQ(std::count(other.err.begin(), other.err.end(), '\n'), 1) << other.err;
  EXPECT_NE(other.err.find("other --set, --vary"), std::string::npos) << other.err;
  EXPECT_EQ(read_file(dir / "study.csv"), before);
}

TEST(SensitivityStudy, BadInputIsOneLineAndStatusTwo) {
  const std::string out = " --out \"" + temp_dir("study-sensitivity-bad").string() + "\"";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"study sensitivity --vary gas.cells_x=4" + out, "--scene"},
      {"study sensitivity " + kTinyBed + out, "--vary"},
      {"study sensitivity " + kTinyBed + " --vary gas.cells_x" + out, "KEY=V1,V2"},
      {"study sensitivity " + kTinyBed + " --vary gas.cells_x,gas.cells_y=4:10,12" + out,
       "has 1 parts for 2 keys"},
      {"study sensitivity " + kTinyBed + " --vary gas.no_such_key=1" + out, "no_such_key"},
      {"study sensitivity " + kTinyBed + " --vary particles.density=-5" + out, "density"},
      {"study coupling --vary gas.cells_x=4" + out, "--vary is for study sensitivity"},
  };
  for (const auto& [args, says] : bad) {
    const CommandResult r = run_fluidbed(args, "study-sens-bad");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.out;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << ": " << r.err;
  }
}
