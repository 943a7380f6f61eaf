// A run that is stopped keeps what it computed and says it did not finish: SIGTERM stops it at the
// end of a step (exit 130, one line, the timeseries so far, status.json "interrupted", no
// summary.json); kill -9 leaves the timeseries flushed so far and status.json "running"; a failed
// run says "failed" with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../test_support.hpp"
#include "run/run_loop.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

const std::string kScene = std::string(FLUIDBED_ASSET_DIR) + "/scenes/packing.toml";

// Starts `fluidbed run SCENE --out DIR`, sends SIGNAL after SECONDS, returns the exit status.
int run_and_signal(const fs::path& dir, const char* signal, int seconds) {
  const std::string cmd = "sh -c '\"" + std::string(FLUIDBED_BINARY) + "\" run \"" + kScene +
                          "\" --out \"" + dir.string() + "\" > \"" + (dir / "out.txt").string() +
                          "\" 2> \"" + (dir / "err.txt").string() + "\" & p=$!; sleep " +
                          std::to_string(seconds) + "; kill -" + signal +
                          " $p; wait $p; echo $? > \"" + (dir / "rc.txt").string() + "\"'";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  return std::stoi(read_file(dir / "rc.txt"));
}

// The rows of a timeseries: every line after the header must be a whole row.
std::vector<std::vector<double>> rows_of(const std::string& csv, std::size_t columns) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
    EXPECT_EQ(v.size(), columns) << line;
    rows.push_back(v);
  }
  return rows;
}

std::size_t header_columns() {
  const std::string h = timeseries_header(false);
  return static_cast<std::size_t>(std::count(h.begin(), h.end(), ',')) + 1;
}

}  // namespace

TEST(Interrupt, SigtermStopsAtAStepAndKeepsTheTimeseries) {
  const fs::path dir = temp_dir("interrupt-term");
  write_file(dir / "summary.json", "{\"status\": \"completed\"}\n");  // an earlier run's
  const int rc = run_and_signal(dir, "TERM", 4);
  const std::string err = read_file(dir / "err.txt");
  ASSERT_EQ(rc, 130) << err;
  EXPECT_EQ(err.rfind("interrupted at t = ", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(dir / "summary.json"));  // never a summary for an unfinished run
  const auto status = nlohmann::json::parse(read_file(dir / "status.json"));
  EXPECT_EQ(status["status"], "interrupted");
  EXPECT_EQ(status["finished"], false);
  const std::string csv = read_file(dir / "timeseries.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n') + 1), timeseries_header(false));
  const auto rows = rows_of(csv, header_columns());
  ASSERT_GE(rows.size(), 1u);
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_GT(rows[k][0], rows[k - 1][0]);
  // The rows are those of a run to the same time, to the last byte.
  const double t_last = rows.back()[0];
  char until[32];
  std::snprintf(until, sizeof until, "%.9g", t_last);
  const fs::path ref = dir / "reference";
  const CommandResult r = run_fluidbed("run " + kScene + " --until " + until + " --out " + ref.string(),
                                       "interrupt-reference");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_file(ref / "timeseries.csv"), csv);
  EXPECT_EQ(nlohmann::json::parse(read_file(ref / "status.json"))["status"], "completed");
  EXPECT_TRUE(fs::exists(ref / "summary.json"));
}

TEST(Interrupt, KillNineLeavesTheTimeseriesSoFarAndSaysRunning) {
  const fs::path dir = temp_dir("interrupt-kill");
  const int rc = run_and_signal(dir, "9", 4);
  EXPECT_EQ(rc, 137);  // killed by signal 9
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  const auto status = nlohmann::json::parse(read_file(dir / "status.json"));
  EXPECT_EQ(status["status"], "running");
  EXPECT_EQ(status["finished"], false);
  const auto rows = rows_of(read_file(dir / "timeseries.csv"), header_columns());
  ASSERT_GE(rows.size(), 1u);  // flushed every second of wall time
  // The csv holds 9 significant digits; status.json the full double of the same time.
  EXPECT_GE(rows.back()[0], status["t_s"].get<double>() * (1.0 - 1e-8));
}

TEST(Interrupt, AFailedRunSaysFailedWithItsReason) {
  const fs::path dir = temp_dir("interrupt-failed");
  const CommandResult r = run_fluidbed(
      "run " + kScene + " --set diagnostics.overlap_limit=1e-4 --out " + dir.string(), "interrupt-failed");
  ASSERT_EQ(r.status, 3) << r.err;
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  const auto status = nlohmann::json::parse(read_file(dir / "status.json"));
  EXPECT_EQ(status["status"], "failed");
  EXPECT_NE(status["reason"].get<std::string>().find("runaway overlap"), std::string::npos);
  EXPECT_NE(read_file(dir / "timeseries.csv").find("t,dp,"), std::string::npos);
}
