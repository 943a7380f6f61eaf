// The regularity measures of a pressure-drop signal, on signals with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/cycles.hpp"

using fluidbed::analyse_cycles;

TEST(Cycles, RegularSignalHasItsPeriodAndNoSpread) {
  // 0.37 s period, sampled every ms for 6 s, with a slow drift and a faster ripple.
  std::vector<double> t, y;
  for (int k = 0; k < 6000; ++k) {
    const double tt = 1.0 + 1e-3 * k;
    t.push_back(tt);
    y.push_back(3000.0 + 50.0 * tt + 400.0 * std::sin(2.0 * M_PI * tt / 0.37) +
                60.0 * std::sin(2.0 * M_PI * 23.0 * tt));
  }
  const auto c = analyse_cycles(t, y);
  ASSERT_TRUE(c.ok);
  EXPECT_NEAR(c.dominant_period, 0.37, 0.37 * 0.01);
  EXPECT_NEAR(c.cycle_mean, 0.37, 0.37 * 0.02);
  EXPECT_LT(c.cycle_cv, 0.03);
  EXPECT_GE(c.cycles, 14);
}

TEST(Cycles, IrregularCyclesShowSpread) {
  // Cycles whose lengths alternate 0.3 s and 0.6 s: mean 0.45 s, spread 0.15 s (cv 1/3).
  std::vector<double> t, y;
  double phase_start = 0.0;
  bool short_cycle = true;
  for (int k = 0; k < 9000; ++k) {
    const double tt = 1e-3 * k;
    double len = short_cycle ? 0.3 : 0.6;
    if (tt - phase_start >= len) {
      phase_start += len;
      short_cycle = !short_cycle;
      len = short_cycle ? 0.3 : 0.6;
    }
    t.push_back(tt);
    y.push_back(std::sin(2.0 * M_PI * (tt - phase_start) / len));
  }
  const auto c = analyse_cycles(t, y);
  ASSERT_TRUE(c.ok);
  EXPECT_NEAR(c.cycle_mean, 0.45, 0.02);
  EXPECT_NEAR(c.cycle_cv, 1.0 / 3.0, 0.03);
  EXPECT_FALSE(analyse_cycles({0.0, 1.0}, {1.0, 2.0}).ok);
}
