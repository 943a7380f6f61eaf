// core/fast_math.hpp against libm: relative error in units of the last place over the domains
// the drag law uses and beyond.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/fast_math.hpp"
#include "core/random.hpp"

namespace fluidbed {
namespace {

// |a - b| in units of the last place of b.
double ulps(double a, double b) {
  const double ulp = std::nextafter(std::fabs(b), std::numeric_limits<double>::infinity()) - std::fabs(b);
  return std::fabs(a - b) / ulp;
}

TEST(FastMath, ExpWithinTwoUlpOfLibm) {
  SplitMix64 rng(7);
  double worst = 0.0, worst_x = 0.0;
  for (int k = 0; k < 1000000; ++k) {
    const double x = -700.0 + 1400.0 * rng.uniform();
    const double e = ulps(fast_exp(x), std::exp(x));
    if (e > worst) worst = e, worst_x = x;
  }
  // Near zero, where the drag law's exponents mostly lie.
  for (int k = 0; k < 1000000; ++k) {
    const double x = -10.0 + 20.0 * rng.uniform();
    const double e = ulps(fast_exp(x), std::exp(x));
    if (e > worst) worst = e, worst_x = x;
  }
  EXPECT_LE(worst, 2.0) << "at x = " << worst_x;
  EXPECT_EQ(fast_exp(0.0), 1.0);
  EXPECT_DOUBLE_EQ(fast_exp(1.0), std::exp(1.0));
}

TEST(FastMath, LogWithinTwoUlpOfLibm) {
  SplitMix64 rng(11);
  double worst = 0.0, worst_x = 0.0;
  for (int k = 0; k < 1000000; ++k) {
    const double x = std::exp(-300.0 + 600.0 * rng.uniform());  // 1e-130 .. 1e130
    const double e = ulps(fast_log(x), std::log(x));
    if (e > worst) worst = e, worst_x = x;
  }
  for (int k = 0; k < 1000000; ++k) {
    const double x = 0.5 + 1.5 * rng.uniform();  // around 1, where ln x is small
    const double l = std::log(x);
    if (l == 0.0) continue;
    const double e = ulps(fast_log(x), l);
    if (e > worst) worst = e, worst_x = x;
  }
  EXPECT_LE(worst, 2.0) << "at x = " << worst_x;
  EXPECT_EQ(fast_log(1.0), 0.0);
  EXPECT_EQ(fast_log(2.0), std::log(2.0));
  EXPECT_DOUBLE_EQ(fast_log(1e-30), std::log(1e-30));
}

}  // namespace
}  // namespace fluidbed
