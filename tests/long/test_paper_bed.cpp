// The paper's bed at U = 2.8 m/s (jet 42 m/s), 3 s from the packed bed (Figs 8, 9-11, 15).
#include <gtest/gtest.h>

#include <algorithm>

#include "../test_support.hpp"
#include "scene/scene_loader.hpp"
#include "analysis/spectrum.hpp"
#include "run/bubble_recorder.hpp"
#include "run/run_loop.hpp"
#include "sim/model_params.hpp"
#include "sim/simulation.hpp"
#include "run/packed_bed.hpp"

using namespace fluidbed;

TEST(PaperBed, JetBedBubblesAroundItsWeight) {
  Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml");
  prepare_packed_bed(s);
  Simulation sim(s);
  const GasGrid grid = gas_grid_for(s);
  const int jet_column = grid.column(0.5 * s.domain.width);
  // The cavity: the highest porosity seen in the cells over the jet inside the packed bed
  // (rows whose centres lie between 2 cm and 16 cm; the packed bed is about 23 cm high).
  double cavity = 0.0;
  const auto& eps = sim.coupler()->porosity();
  std::vector<TimeseriesRow> rows;
  // The bubble analysis at its default interval, 10 ms: once per chunk.
  BubbleRecorder bubbles(sim);
  bubbles.analyse(sim);
  for (int k = 1; k <= 300; ++k) {  // 3 s in chunks of 10 ms, looking at the cavity after each
    RunOptions chunk;
    chunk.until = 0.01 * k;
    const RunResult part = run_simulation(sim, chunk);
    rows.insert(rows.end(), part.rows.begin(), part.rows.end());
    bubbles.analyse(sim);
    for (int j = 0; j < grid.ny; ++j) {
      const double y = (j + 0.5) * grid.dy();
      if (y < 0.02 || y > 0.16) continue;
      cavity = std::max(cavity, eps[static_cast<std::size_t>(grid.index(jet_column, j))]);
    }
  }
  // Start-up peak, later mean and overlaps from the rows (one per millisecond; each row holds
  // the largest overlap of its millisecond).
  double peak = 0.0, sum = 0.0, overlap_start = 0.0;
  std::vector<double> overlap_after;
  for (const auto& row : rows) {
    if (row.t < 1.0) {
      peak = std::max(peak, row.dp);
      overlap_start = std::max(overlap_start, row.max_overlap_ratio);
    } else {
      sum += row.dp;
      overlap_after.push_back(row.max_overlap_ratio);
    }
  }
  std::sort(overlap_after.begin(), overlap_after.end());
  const double mean = sum / static_cast<double>(overlap_after.size()), weight = 3550.35;
  const double p99 = overlap_after[overlap_after.size() * 99 / 100];
  const double worst = overlap_after.back();
  const auto above = std::count_if(overlap_after.begin(), overlap_after.end(),
                                   [](double o) { return o > 0.01; });
  std::printf("paper bed, 3 s: start-up peak %.0f Pa, mean dp (1-3 s) %.0f Pa (weight/area %.0f, "
              "%+.1f %%), max overlap %.2f %% at start-up; after: 99th percentile of the "
              "millisecond maxima %.2f %%, largest %.2f %% (%ld of %zu ms above 1 %%), cavity "
              "porosity %.3f\n", peak, mean, weight, 100.0 * (mean / weight - 1.0),
              100.0 * overlap_start, 100.0 * p99, 100.0 * worst, static_cast<long>(above),
              overlap_after.size(), cavity);
  EXPECT_GT(peak, 1.25 * mean);
  EXPECT_NEAR(mean, weight, 0.2 * weight);
  // The paper (Fig. 15): "except for 1.7 % at start-up, well below 1 %". Its figure shows the
  // fluctuating level; ours stays below 1 % in 99 % of the milliseconds after start-up, with
  // rare single collisions slightly above (reported above and in the closing note, not hidden).
  EXPECT_LT(p99, 0.01);
  EXPECT_LT(worst, 0.02);
  EXPECT_GT(cavity, 0.8);

  // Bubbles are found and tracked, and they erupt at the surface about as often as dp swings
  // (the dominant frequency of its Welch spectrum after start-up): within 25 %.
  const nlohmann::json b = bubbles.bubbles_summary(1.0);
  std::vector<double> dp_after;
  for (const auto& row : rows)
    if (row.t > 1.0) dp_after.push_back(row.dp);
  const PowerSpectrum sp = welch_spectrum(dp_after, rows[1].t - rows[0].t);
  const double f_dp = sp.dominant_frequency_refined;
  const double eruptions = b["eruptions_per_s"].get<double>();
  std::printf("bubbles (1-3 s): %d formed (%.1f per s), mean D_e %.1f mm, mean rise velocity %.3f "
              "m/s (2D relation 0.5 sqrt(g D_e): %.3f m/s), eruptions %.2f per s against the "
              "dominant dp frequency %.2f Hz (%+.0f %%), slugging fraction %.2f, regime %s\n",
              b["formed"].get<int>(), b["formed_per_s"].get<double>(),
              1e3 * b["mean_d_eq_m"].get<double>(), b["mean_rise_velocity_m_s"].get<double>(),
              b["mean_rise_velocity_2d_ref_m_s"].get<double>(), eruptions, f_dp,
              100.0 * (eruptions / f_dp - 1.0), b["slugging_fraction"].get<double>(),
              b["regime"].get<std::string>().c_str());
  EXPECT_GT(b["formed"].get<int>(), 10);
  EXPECT_GT(b["velocity_samples"].get<int>(), 50);
  EXPECT_GT(b["mean_d_eq_m"].get<double>(), 2.0 * s.particles.diameter);
  EXPECT_NEAR(eruptions, f_dp, 0.25 * f_dp);
}
