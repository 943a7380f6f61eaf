// The bubble analysis wired into runs (`run --bubbles`): the outputs a user gets, the regimes of
// a bed at rest and of a bed below minimum fluidization, and bad [bubbles] settings.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>
#include <sstream>

#include "../test_support.hpp"
#include "run/packed_bed.hpp"
#include "run/run_loop.hpp"
#include "scene/scene_loader.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

RunResult run_with_bubbles(const std::string& scene, const std::vector<std::string>& overrides,
                           double until) {
  Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/" + scene, overrides);
  prepare_packed_bed(s);
  Simulation sim(s);
  RunOptions o;
  o.until = until;
  o.bubbles = true;
  return run_simulation(sim, o);
}

}  // namespace

// The packed bed with the gas off: particles at rest, nothing void inside the bed.
TEST(BubblesRun, PackedBedAtRestHasNoBubbles) {
  const RunResult r = run_with_bubbles(
      "teaching.toml", {"gas.enabled=false", "diagnostics.averaging_start=0.02"}, 0.1);
  const auto& b = r.summary["bubbles"];
  EXPECT_EQ(b["formed"].get<int>(), 0);
  EXPECT_EQ(b["bubble_frames"].get<int>(), 0);
  EXPECT_EQ(b["regime"], "fixed");
  EXPECT_TRUE(r.bubble_rows.empty());
  // A frame every 10 ms, the start included, up to the run's last step (its step count is the
  // nearest to 0.1 s: 2108 steps of 4.743e-5 s end at 0.09998 s, before the last frame).
  const double end = r.summary["end_time_s"].get<double>();
  ASSERT_EQ(r.mixing.size(), 1u + static_cast<std::size_t>(std::floor(end / 0.01 + 1e-9)));
  // Nothing moves: the halves by initial height stay apart.
  EXPECT_LT(r.mixing.back().index, 0.2);
}

// Below minimum fluidization (U = 1.0 m/s, the paper's U_mf is 1.8 m/s) the jet may hold a
// cavity but no bubble leaves it: the regime is "fixed". The teaching scene's settings keep the
// run short.
TEST(BubblesRun, BedBelowMinimumFluidizationIsFixed) {
  const RunResult r = run_with_bubbles(
      "teaching.toml", {"inlet.superficial_velocity=1.0", "diagnostics.averaging_start=0.4"}, 0.8);
  const auto& b = r.summary["bubbles"];
  std::printf("U = 1.0 m/s: formed %d, slugging fraction %.2f, jet cavity fraction %.2f, regime %s\n",
              b["formed"].get<int>(), b["slugging_fraction"].get<double>(),
              b["jet_cavity_fraction"].get<double>(), b["regime"].get<std::string>().c_str());
  EXPECT_EQ(b["regime"], "fixed");
}

// What `run --bubbles` writes, and the one-line refusals of impossible [bubbles] values.
TEST(BubblesRun, CommandLineWritesTheBubbleFiles) {
  const auto dir = temp_dir("bubbles-cli");
  const CommandResult r = run_fluidbed(
      "run " + std::string(FLUIDBED_ASSET_DIR) +
          "/scenes/teaching.toml --until 0.3 --bubbles --set diagnostics.averaging_start=0.1 "
          "--out " + (dir / "run").string(),
      "bubbles-cli-run");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = read_file(dir / "run" / "bubbles.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,id,x,y,d_eq,area,width,height,vx,vy,event");
  const std::string mixing = read_file(dir / "run" / "mixing.csv");
  EXPECT_EQ(mixing.substr(0, mixing.find('\n')), "t,lacey_index");
  const std::string ts = read_file(dir / "run" / "timeseries.csv");
  const std::string header = ts.substr(0, ts.find('\n'));
  EXPECT_NE(header.find(",bubbles,regime"), std::string::npos) << header;
  const auto summary = nlohmann::json::parse(read_file(dir / "run" / "summary.json"));
  for (const char* key : {"formed_per_s", "eruptions_per_s", "mean_d_eq_m",
                          "mean_rise_velocity_m_s", "slugging_fraction", "regime"})
    EXPECT_TRUE(summary["bubbles"].contains(key)) << key;
  EXPECT_TRUE(summary.contains("dp_spectrum"));

  for (const std::string bad : {"bubbles.threshold=1.5", "bubbles.interval=0", "bubbles.foo=1",
                                "bubbles.min_diameter=-0.01"}) {
    const CommandResult e = run_fluidbed("run " + std::string(FLUIDBED_ASSET_DIR) +
                                             "/scenes/drop.toml --bubbles --set " + bad + " --out " +
                                             (dir / "bad").string(),
                                         "bubbles-cli-bad");
    EXPECT_EQ(e.status, 2) << bad;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << e.err;
    EXPECT_NE(e.err.find("bubbles."), std::string::npos) << e.err;
  }
}
