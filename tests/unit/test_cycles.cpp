// The regularity measures of a pressure-drop signal, on signals with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <random>

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

namespace {

// 6 s of a signal sampled every ms from t = 1 s, as a run's dp after start-up.
template <class F>
fluidbed::CycleStats cycles_of(F signal,
                               fluidbed::CycleAmplitude against = fluidbed::CycleAmplitude::mean) {
  std::vector<double> t, y;
  for (int k = 0; k < 6000; ++k) {
    const double tt = 1.0 + 1e-3 * k;
    t.push_back(tt);
    y.push_back(signal(tt, k));
  }
  return analyse_cycles(t, y, against);
}

}  // namespace

TEST(Cycles, NoiseAloneIsNoRegularCycle) {
  // White noise of 300 Pa on 3000 Pa, ten seeds: the highest peak is always somewhere, never a
  // cycle.
  double worst = 0.0;
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 300.0);
    const auto c = cycles_of([&](double, int) { return 3000.0 + noise(rng); });
    ASSERT_TRUE(c.ok);
    EXPECT_FALSE(c.regular) << "seed " << seed << ": " << c.verdict;
    EXPECT_LT(c.peak_prominence, fluidbed::kProminence) << "seed " << seed;
    EXPECT_EQ(c.verdict.rfind("no regular cycle", 0), 0u) << c.verdict;
    worst = std::max(worst, c.peak_prominence);
  }
  std::printf("white noise: highest prominence of ten records %.1f\n", worst);
}

TEST(Cycles, RedNoiseIsNoRegularCycle) {
  // A random walk pulled back to its mean (Ornstein-Uhlenbeck, relaxation time 0.05 s, spread
  // 1500 Pa): a red spectrum whose low frequencies stand far above the median of the band, but
  // not above their own surroundings. Ten seeds.
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> kick(0.0, 1.0);
    const double tau = 0.05, step = 1500.0 * std::sqrt(2.0 * 1e-3 / tau);
    double x = 0.0;
    const auto c = cycles_of([&](double, int) {
      x += -x * 1e-3 / tau + step * kick(rng);
      return 3000.0 + x;
    });
    ASSERT_TRUE(c.ok);
    EXPECT_FALSE(c.regular) << "seed " << seed << ": " << c.verdict;
    EXPECT_GT(c.amplitude_share, fluidbed::kAmplitudeShare);  // the size alone would pass
    std::printf("red noise, seed %u: %s (prominence %.1f)\n", seed, c.verdict.c_str(), c.peak_prominence);
  }
}

TEST(Cycles, SlowDriftIsNoRegularCycle) {
  // dp relaxing over the record (an exponential the least-squares line does not remove) with a
  // little noise: the highest peak is at the record's length, too slow to be a cycle.
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 20.0);
  const auto c = cycles_of([&](double t, int) { return 2800.0 + 600.0 * std::exp(-(t - 1.0) / 1.5) + noise(rng); });
  ASSERT_TRUE(c.ok);
  EXPECT_FALSE(c.regular) << c.verdict;
  std::printf("drift: %s\n", c.verdict.c_str());
}

TEST(Cycles, ClearPeriodInNoiseIsARegularCycle) {
  // The ideal bed of Fig. 17: a 0.45 s cycle of +-1500 Pa on 3000 Pa, with noise of 400 Pa.
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 400.0);
  const auto c = cycles_of([&](double t, int) { return 3000.0 + 1500.0 * std::sin(2.0 * M_PI * t / 0.45) + noise(rng); });
  ASSERT_TRUE(c.ok);
  EXPECT_TRUE(c.regular) << c.verdict;
  EXPECT_EQ(c.verdict, "regular cycle");
  EXPECT_NEAR(c.dominant_period, 0.45, 0.45 * 0.05);
  EXPECT_NEAR(c.amplitude, 1500.0, 1500.0 * 0.05);
}

TEST(Cycles, SmallOscillationIsNoRegularCycle) {
  // A clean period that moves dp by 2 % of its mean: prominent, but not the bed's cycle.
  const auto c = cycles_of([&](double t, int) { return 3000.0 + 60.0 * std::sin(2.0 * M_PI * t / 0.45); });
  ASSERT_TRUE(c.ok);
  EXPECT_GT(c.peak_prominence, fluidbed::kProminence);
  EXPECT_FALSE(c.regular) << c.verdict;
  EXPECT_NE(c.verdict.find("of the mean"), std::string::npos) << c.verdict;
}

TEST(Cycles, AProbesCycleIsJudgedAgainstItsStandardDeviation) {
  using fluidbed::CycleAmplitude;
  // A probe's pressure against the outlet: 3000 Pa of bed above it and a 0.43 s cycle of 116 Pa
  // (a standard deviation of 82 Pa, van Wachem's measured one) with 20 Pa of noise. Against the
  // mean the swing is 4 %, no cycle; against the standard deviation it is 1.4 times it, a cycle.
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 20.0);
  std::vector<double> y;
  for (int k = 0; k < 6000; ++k)
    y.push_back(3000.0 + 116.0 * std::sin(2.0 * M_PI * (1.0 + 1e-3 * k) / 0.43) + noise(rng));
  const auto by_mean = cycles_of([&](double, int k) { return y[k]; });
  EXPECT_FALSE(by_mean.regular);
  EXPECT_NE(by_mean.verdict.find("of the mean"), std::string::npos) << by_mean.verdict;
  const auto by_std = cycles_of([&](double, int k) { return y[k]; }, CycleAmplitude::std);
  EXPECT_TRUE(by_std.regular) << by_std.verdict;
  EXPECT_NEAR(by_std.dominant_period, 0.43, 0.43 * 0.05);
  EXPECT_NEAR(by_std.amplitude_share, 116.0 / std::hypot(116.0 / std::sqrt(2.0), 20.0), 0.05);
  // The same verdict with the mean taken off (the measured "relative pressure"): the mean
  // plays no part.
  const auto relative =
      cycles_of([&](double, int k) { return y[k] - 3000.0; }, CycleAmplitude::std);
  EXPECT_TRUE(relative.regular) << relative.verdict;

  // A clean 50 Pa tone under 420 Pa of fast noise (white noise differenced: its power is at high
  // frequencies, so the tone stands far above its own neighbourhood) is no cycle of the probe:
  // it carries 0.7 % of the signal's variance.
  std::normal_distribution<double> white(0.0, 300.0);
  double last = 0.0;
  const auto tone = cycles_of(
      [&](double t, int) {
        const double w = white(rng), d = w - last;
        last = w;
        return 50.0 * std::sin(2.0 * M_PI * t / 0.45) + d;
      },
      CycleAmplitude::std);
  ASSERT_TRUE(tone.ok);
  EXPECT_NEAR(tone.dominant_period, 0.45, 0.45 * 0.05);
  EXPECT_GT(tone.peak_prominence, fluidbed::kProminence);
  EXPECT_FALSE(tone.regular);
  EXPECT_NE(tone.verdict.find("of the standard deviation (50 % needed)"), std::string::npos)
      << tone.verdict;
}
