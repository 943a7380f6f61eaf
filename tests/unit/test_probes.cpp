// Pressure probes and the bed top (analysis/pressure_probe.hpp, analysis/packing_metrics.hpp):
// the probe against a pressure field made by hand, with its clamping at the walls and its outlet
// reference; the highest centre of spheres placed by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "../test_support.hpp"
#include "analysis/packing_metrics.hpp"
#include "analysis/pressure_probe.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

// 4 x 3 cells of 10 x 20 mm: centres at x = 5, 15, 25, 35 mm and y = 10, 30, 50 mm.
GasGrid probe_grid() {
  GasGrid g;
  g.nx = 4;
  g.ny = 3;
  g.width = 0.04;
  g.height = 0.06;
  return g;
}

// Rows bottom to top, as the solver numbers cells (c = j nx + i); the top row's mean is 25 Pa.
const std::vector<double> kProbeField = {
    100.0, 110.0, 130.0, 160.0,  // j = 0
    60.0,  70.0,  80.0,  90.0,   // j = 1
    10.0,  20.0,  30.0,  40.0,   // j = 2 (the outlet row: mean 25)
};
constexpr double kProbeOutlet = 25.0;  // Pa

}  // namespace

TEST(Probes, BilinearBetweenTheFourCentresAroundThePoint) {
  const GasGrid g = probe_grid();
  // On a centre: that cell's pressure.
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.015, 0.030), 70.0 - kProbeOutlet, 1e-12);
  // Halfway between the centres (15, 10) and (25, 10) mm: (110 + 130) / 2.
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.020, 0.010), 120.0 - kProbeOutlet, 1e-12);
  // A quarter of the way from x = 25 to 35 mm and three quarters from y = 10 to 30 mm:
  //   bottom 130 + 0.25 (160 - 130) = 137.5, top 80 + 0.25 (90 - 80) = 82.5,
  //   137.5 + 0.75 (82.5 - 137.5) = 96.25.
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.0275, 0.025), 96.25 - kProbeOutlet, 1e-12);
  // A field linear in x and y is reproduced exactly anywhere between the centres.
  std::vector<double> linear(12);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      linear[g.index(i, j)] = 500.0 + 2000.0 * (i + 0.5) * g.dx() - 3000.0 * (j + 0.5) * g.dy();
  const double outlet = 500.0 + 2000.0 * 0.02 - 3000.0 * 0.05;  // the top row's mean
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0.012, 0.017}, {0.031, 0.044}})
    EXPECT_NEAR(probe_pressure(g, linear, x, y), 500.0 + 2000.0 * x - 3000.0 * y - outlet, 1e-9)
        << x << ", " << y;
}

TEST(Probes, ClampedToTheCentresNextToAWall) {
  const GasGrid g = probe_grid();
  // Between the left wall and the first column of centres: that column's value, not an
  // extrapolation (halfway between y = 10 and 30 mm: (100 + 60) / 2).
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.0, 0.020), 80.0 - kProbeOutlet, 1e-12);
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.003, 0.020), 80.0 - kProbeOutlet, 1e-12);
  // The right wall: the last column ((160 + 90) / 2).
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.04, 0.020), 125.0 - kProbeOutlet, 1e-12);
  // The corners: the corner cells.
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.0, 0.0), 100.0 - kProbeOutlet, 1e-12);
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.04, 0.0), 160.0 - kProbeOutlet, 1e-12);
  // At the top (the outlet face), the top row between its centres: (20 + 30) / 2 - 25 = 0.
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.02, 0.06), 0.0, 1e-12);
  EXPECT_NEAR(probe_pressure(g, kProbeField, 0.0, 0.06), 10.0 - kProbeOutlet, 1e-12);
}

TEST(Probes, MeasuredAgainstTheMeanOfTheTopRow) {
  const GasGrid g = probe_grid();
  // A field that is uniform in x reads the same wherever across the bed, and a constant added
  // to the whole field (the absolute pressure) changes nothing.
  std::vector<double> field(12), shifted(12);
  for (int c = 0; c < 12; ++c) {
    field[c] = 300.0 - 100.0 * (c / 4);
    shifted[c] = field[c] + 101325.0;
  }
  for (double x : {0.0, 0.013, 0.04}) {
    EXPECT_NEAR(probe_pressure(g, field, x, 0.01), 200.0, 1e-12) << x;
    EXPECT_NEAR(probe_pressure(g, shifted, x, 0.01), 200.0, 1e-9) << x;
  }
}

TEST(BedTop, TheHighestSphereCentre) {
  // Five spheres by hand: the highest centre is 0.123 m, wherever across the bed it is; the
  // column-mean height (1 cm columns) is lower, since it averages every column's top.
  const Particles p = make_particles({{0.010, 0.020, 0, 0, 0},
                                      {0.030, 0.050, 0, 0, 0},
                                      {0.075, 0.123, 0, 0, 0},
                                      {0.120, 0.080, 0, 0, 0},
                                      {0.140, 0.002, 0, 0, 0}});
  EXPECT_EQ(bed_top(p), 0.123);
  EXPECT_LT(measure_packing(p, 0.15, 0.004).bed_height, bed_top(p));
  EXPECT_EQ(bed_top(make_particles({{0.05, 0.3, 0, 0, 0}})), 0.3);
  EXPECT_EQ(bed_top(Particles{}), 0.0);
}
