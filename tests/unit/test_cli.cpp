// The fluidbed binary itself: bad input ends with status 2 and one line naming the problem; a good
// run writes the contract's files.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../test_support.hpp"

using namespace fluidbed::testing;

namespace {

void expect_refused(const std::string& args, const std::string& needle, const std::string& tag) {
  const CommandResult r = run_fluidbed(args, tag);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  // One line.
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

TEST(Cli, BadInputExitsWithStatusTwo) {
  const auto dir = temp_dir("cli-bad");
  write_file(dir / "unknown.toml", "[particles]\ncount = 10\ncolour = \"red\"\n");
  write_file(dir / "negative.toml", "[particles]\ndiameter = -0.004\n");
  write_file(dir / "crowded.toml", "[particles]\ncount = 9000\n");
  const auto out = (dir / "o").string();
  expect_refused("run " + (dir / "unknown.toml").string() + " --out " + out, "particles.colour", "a");
  expect_refused("run " + (dir / "negative.toml").string() + " --out " + out, "particles.diameter", "b");
  expect_refused("run " + (dir / "crowded.toml").string() + " --out " + out, "particles.count", "c");
  expect_refused("run " + (dir / "missing.toml").string() + " --out " + out, "missing.toml", "d");
  write_file(dir / "fine.toml", "[particles]\ncount = 10\n");
  expect_refused("run " + (dir / "fine.toml").string() + " --out " + out + " --set particles.count=x",
                 "particles.count", "e");
  expect_refused("frobnicate", "frobnicate", "f");
  EXPECT_FALSE(std::filesystem::exists(dir / "o" / "summary.json"));
}

TEST(Cli, RunWritesSummaryAndTimeseries) {
  const auto dir = temp_dir("cli-run");
  const CommandResult r = run_fluidbed("run " + std::string(FLUIDBED_ASSET_DIR) +
                                           "/scenes/drop.toml --until 0.15 --out " + dir.string(),
                                       "run");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(read_file(dir / "summary.json"));
  for (const char* key : {"particles", "steps", "sim_time_s", "wall_time_s", "wall_s_per_sim_s",
                          "particle_steps_per_s", "max_overlap_ratio", "restitution",
                          "rebound_height_ratio", "bed_weight_per_area_pa", "averaging_start_s"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["particles"].get<int>(), 1);
  EXPECT_EQ(j["steps"].get<int>(), 10000);
  const std::string csv = read_file(dir / "timeseries.csv");
  EXPECT_EQ(csv.rfind("t,dp,max_overlap_ratio,", 0), 0u);
  EXPECT_NE(csv.find("kinetic_energy"), std::string::npos);
  EXPECT_NE(csv.find("contacts"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "scene.toml"));
}

TEST(Cli, VersionNamesTheProjectVersionAndCommit) {
  const CommandResult r = run_fluidbed("--version", "version");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("fluidbed " + std::string(FLUIDBED_VERSION) + " (commit ", 0), 0u) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  // The commit the sources are at, as git tells it here ("unknown" outside a checkout).
  std::string head;
  if (FILE* git = ::popen(("git -C " + std::string(FLUIDBED_SOURCE_DIR) +
                           " rev-parse HEAD 2>/dev/null").c_str(), "r")) {
    char buf[128];
    while (std::fgets(buf, sizeof buf, git) != nullptr) head += buf;
    if (::pclose(git) != 0) head.clear();
  }
  while (!head.empty() && (head.back() == '\n' || head.back() == ' ')) head.pop_back();
  if (head.empty()) head = "unknown";
  EXPECT_NE(r.out.find("(commit " + head), std::string::npos) << r.out << " expected " << head;
}
