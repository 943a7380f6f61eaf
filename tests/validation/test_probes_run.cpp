// Pressure probes and the bed top in a run: the timeseries columns p_probe_N and bed_top, the
// summary's `probes` list and bed_top_* figures, the probes' spectra in dp_spectrum.csv, and no
// bit of the run changed by them (the same state hash and the same other columns with and
// without probes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../test_support.hpp"
#include "run/run_loop.hpp"
#include "scene/scene_loader.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

// The small bed landing on the jet of test_support.hpp, 0.12 s (0.15 s of wall time).
const std::string kProbeScene = small_jet_bed_toml("probes-test");

// Under the bed beside the jet, and above the bed.
const std::string kProbeSet = "diagnostics.probes=[[0.045, 0.015], [0.075, 0.25]]";

std::vector<std::string> probe_csv_header(const std::string& csv) {
  std::vector<std::string> names;
  std::stringstream line(csv.substr(0, csv.find('\n')));
  for (std::string c; std::getline(line, c, ',');) names.push_back(c);
  return names;
}

// One column of a CSV's rows, by name.
std::vector<double> probe_csv_column(const std::string& csv, const std::string& name) {
  const std::vector<std::string> h = probe_csv_header(csv);
  const auto col = static_cast<std::size_t>(std::find(h.begin(), h.end(), name) - h.begin());
  std::vector<double> v;
  std::stringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream cells(line);
    std::string c;
    for (std::size_t k = 0; k <= col && std::getline(cells, c, ','); ++k) {
    }
    v.push_back(std::stod(c));
  }
  return v;
}

}  // namespace

TEST(ProbesRun, ProbesAndTheBedTopChangeNoBitOfTheRun) {
  const Settings plain = parse_scene(kProbeScene, "probes.toml");
  const Settings probed = parse_scene(kProbeScene, "probes.toml", {kProbeSet});
  Simulation a(plain), b(probed);
  const RunResult ra = run_simulation(a, RunOptions{});
  const RunResult rb = run_simulation(b, RunOptions{});
  EXPECT_EQ(a.state_hash(), b.state_hash());
  EXPECT_EQ(ra.summary["state_hash"], rb.summary["state_hash"]);
  // Every other column the same, row by row (as written, and the doubles to the bit); the probed
  // rows carry two values more.
  ASSERT_EQ(ra.rows.size(), rb.rows.size());
  for (std::size_t k = 0; k < ra.rows.size(); ++k) {
    TimeseriesRow without = rb.rows[k];
    without.probes.clear();
    EXPECT_EQ(timeseries_line(ra.rows[k], false), timeseries_line(without, false)) << "row " << k;
    const TimeseriesRow &x = ra.rows[k], &y = rb.rows[k];
    for (auto f : {&TimeseriesValues::t, &TimeseriesValues::dp, &TimeseriesValues::kinetic_energy,
                   &TimeseriesValues::fluid_force_y, &TimeseriesValues::bed_height,
                   &TimeseriesValues::bed_top})
      EXPECT_EQ(x.*f, y.*f) << "row " << k;
    EXPECT_TRUE(x.probes.empty());
    ASSERT_EQ(y.probes.size(), 2u);
  }
  // The summaries differ by the probes only.
  nlohmann::json sa = ra.summary, sb = rb.summary;
  for (const char* k : {"wall_time_s", "wall_s_per_sim_s", "particle_steps_per_s"}) {
    sa.erase(k);
    sb.erase(k);
  }
  EXPECT_FALSE(sa.contains("probes"));
  ASSERT_TRUE(sb.contains("probes"));
  sb.erase("probes");
  EXPECT_EQ(sa, sb);

  // The bed top is the highest centre at the row; the last row is the run's end.
  const Particles& p = b.dem().particles();
  EXPECT_EQ(rb.rows.back().bed_top, *std::max_element(p.y.begin(), p.y.end()));
  EXPECT_GE(rb.rows.back().bed_top, rb.rows.back().bed_height);
  // The last row is the run's end: the first probe, (0.045, 0.015) m, is on the centre line of
  // column 4 (centres every 10 mm from 5 mm) a quarter of the way from row 0's centres (10 mm)
  // to row 1's (30 mm, cells 20 mm high), against the mean of the top row.
  const std::vector<double>& pg = b.gas()->pressure();
  double outlet = 0.0;
  for (int i = 0; i < 15; ++i) outlet += pg[14 * 15 + i] / 15.0;
  EXPECT_NEAR(rb.rows.back().probes[0], 0.75 * pg[4] + 0.25 * pg[15 + 4] - outlet, 1e-9);
  // Above the bed the pressure is the outlet's within the gas's own weight and drag: a few Pa,
  // against the bed's 445 Pa per area.
  for (const TimeseriesRow& r : rb.rows) EXPECT_LT(std::fabs(r.probes[1]), 20.0) << r.t;
}

TEST(ProbesRun, TheColumnsTheSummaryAndTheSpectraOfARunWithProbes) {
  const fs::path dir = temp_dir("probes-run");
  write_file(dir / "probes.toml", kProbeScene);
  const CommandResult r = run_fluidbed("run " + (dir / "probes.toml").string() + " --set '" +
                                           kProbeSet + "' --plots --out " + (dir / "out").string(),
                                       "probes-run");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = read_file(dir / "out" / "timeseries.csv");
  const std::vector<std::string> h = probe_csv_header(csv);
  for (const char* c : {"bed_height", "bed_top", "p_probe_1", "p_probe_2"})
    EXPECT_NE(std::find(h.begin(), h.end(), c), h.end()) << c << " in " << csv.substr(0, 400);
  EXPECT_EQ(std::find(h.begin(), h.end(), "p_probe_3"), h.end());

  const auto j = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  ASSERT_TRUE(j.contains("probes")) << j.dump(2);
  ASSERT_EQ(j["probes"].size(), 2u);
  const std::vector<double> p1 = probe_csv_column(csv, "p_probe_1");
  const std::vector<double> t = probe_csv_column(csv, "t");
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] > 0.04) {
      sum += p1[k];
      ++n;
    }
  for (const auto& e : j["probes"])
    for (const char* key : {"column", "point_m", "mean_pa", "std_pa", "peak_hz", "spectrum",
                            "peak_period_s", "dominant_period_s", "cycle", "peak_prominence",
                            "peak_amplitude_pa", "peak_amplitude_share"})
      EXPECT_TRUE(e.contains(key)) << key << " in " << e.dump();
  const auto& first = j["probes"][0];
  EXPECT_EQ(first["column"], "p_probe_1");
  EXPECT_EQ(first["point_m"], nlohmann::json({0.045, 0.015}));
  // The mean over the rows after start-up, from the column's 9 significant digits.
  EXPECT_NEAR(first["mean_pa"].get<double>(), sum / n, 1e-6 * std::fabs(sum / n));
  EXPECT_GT(first["std_pa"].get<double>(), 0.0);
  EXPECT_EQ(first["cycle"].get<std::string>().rfind("no regular cycle", 0), 0u) << first["cycle"];

  // The bed top's figures over the same rows.
  const std::vector<double> top = probe_csv_column(csv, "bed_top");
  double lo = 1e9, hi = -1e9;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] > 0.04) {
      lo = std::min(lo, top[k]);
      hi = std::max(hi, top[k]);
    }
  // The column has 6 significant digits: half a unit of the last is 5e-6 of the value at most.
  EXPECT_NEAR(j["bed_top_min_m"].get<double>(), lo, 5e-6 * lo);
  EXPECT_NEAR(j["bed_top_max_m"].get<double>(), hi, 5e-6 * hi);
  EXPECT_GE(j["bed_top_mean_m"].get<double>(), j["bed_top_min_m"].get<double>());
  EXPECT_LE(j["bed_top_mean_m"].get<double>(), j["bed_top_max_m"].get<double>());
  EXPECT_TRUE(j.contains("bed_top_peak_hz"));
  EXPECT_GT(j["bed_top_mean_m"].get<double>(), j["bed_height_mean_m"].get<double>());

  // dp's spectrum and each probe's, on the same bins.
  const std::string spectrum = read_file(dir / "out" / "dp_spectrum.csv");
  EXPECT_EQ(spectrum.substr(0, spectrum.find('\n')), "f,psd,psd_probe_1,psd_probe_2");
  EXPECT_EQ(probe_csv_column(spectrum, "psd_probe_2").size(),
            probe_csv_column(spectrum, "psd").size());
  EXPECT_TRUE(fs::exists(dir / "out" / "dp_spectrum.png"));
  // The resolved scene keeps the probes.
  EXPECT_NE(read_file(dir / "out" / "scene.toml").find("probes = [["), std::string::npos);
}
