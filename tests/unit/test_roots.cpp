// False position (core/roots.hpp), as the studies and the coupled-bed test find U_mf with it.
#include <gtest/gtest.h>

#include <cmath>

#include "core/roots.hpp"

using fluidbed::false_position;
using fluidbed::RootBracket;

TEST(FalsePosition, KeepsTheBracketAndNarrowsOnTheRoot) {
  int calls = 0;
  auto f = [&](double x) {
    ++calls;
    return x * x - 2.0;
  };
  const RootBracket b = false_position(f, 1.0, 2.0, 30, 1e-12);
  EXPECT_LE(b.lo, std::sqrt(2.0));
  EXPECT_GE(b.hi, std::sqrt(2.0));
  EXPECT_LT(b.flo, 0.0);
  EXPECT_GT(b.fhi, 0.0);
  EXPECT_NEAR(b.secant_root(), std::sqrt(2.0), 1e-12);
  EXPECT_EQ(calls, 32);  // both ends, then one a step (false position keeps one end here)
  // The first step by hand: the secant through (1, -1) and (2, 2) crosses at 4/3.
  const RootBracket one = false_position(f, 1.0, 2.0, 1, 0.0);
  EXPECT_DOUBLE_EQ(one.lo, 4.0 / 3.0);
  EXPECT_DOUBLE_EQ(one.hi, 2.0);
  // A bracket already narrower than the width is not stepped.
  calls = 0;
  false_position(f, 1.41, 1.42, 10, 0.1);
  EXPECT_EQ(calls, 2);
}
