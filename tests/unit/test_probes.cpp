// Pressure probes and the bed top (diagnostics.probes; analysis/pressure_probe.hpp,
// analysis/packing_metrics.hpp): the probe against a pressure field made by hand, with its
// clamping at the walls and its outlet reference; the key read from a scene and from --set,
// written back, and refused in one line where it cannot be measured; the highest centre of
// spheres placed by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "../test_support.hpp"
#include "analysis/packing_metrics.hpp"
#include "analysis/pressure_probe.hpp"
#include "core/errors.hpp"
#include "scene/scene_loader.hpp"

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

TEST(Probes, ReadFromTheSceneAndFromSetAndWrittenBack) {
  const Settings s =
      parse_scene("[gas]\n[diagnostics]\nprobes = [[0.045, 0.045], [0.075, 0.1]]\n", "t.toml");
  ASSERT_EQ(s.diagnostics.probes.size(), 2u);
  EXPECT_EQ(s.diagnostics.probes[1], (ProbePoint{0.075, 0.1}));
  const Settings set = parse_scene("[gas]\n", "t.toml", {"diagnostics.probes=[[0.045, 0.045]]"});
  ASSERT_EQ(set.diagnostics.probes.size(), 1u);
  EXPECT_EQ(set.diagnostics.probes[0], (ProbePoint{0.045, 0.045}));
  // Integers read as numbers; the resolved scene reads back as itself.
  EXPECT_EQ(parse_scene("[gas]\n", "t.toml", {"diagnostics.probes=[[0, 0]]"}).diagnostics.probes[0],
            (ProbePoint{0.0, 0.0}));
  const std::string text = to_toml(s);
  EXPECT_NE(text.find("probes = [["), std::string::npos) << text;
  EXPECT_EQ(parse_scene(text, "resolved.toml").diagnostics.probes, s.diagnostics.probes);
  // No probes: the resolved scene has no line for them (its text, which the packed-bed cache
  // is keyed on, is what it was before the key existed).
  EXPECT_EQ(to_toml(Settings{}).find("probes"), std::string::npos);
}

TEST(Probes, RefusedInOneLineNamingTheProbe) {
  const auto error_of = [](const std::string& scene, const std::string& set) {
    return fluidbed::testing::scene_error(scene, {set});
  };
  // The paper's box is 0.15 x 0.9 m.
  std::string e = error_of("[gas]\n", "diagnostics.probes=[[0.05, 0.1], [0.2, 0.05]]");
  EXPECT_NE(e.find("diagnostics.probes"), std::string::npos) << e;
  EXPECT_NE(e.find("diagnostics.probes has probe 2 at (0.2, 0.05) m outside the gas domain"),
            std::string::npos)
      << e;
  e = error_of("[gas]\n", "diagnostics.probes=[[0.05, -0.01]]");
  EXPECT_NE(e.find("probe 1 at (0.05, -0.01) m outside"), std::string::npos) << e;
  e = error_of("", "diagnostics.probes=[[0.05, 0.1]]");  // no [gas]
  EXPECT_NE(e.find("probe 1 at (0.05, 0.1) m but the scene has no gas"), std::string::npos) << e;
  for (const char* bad : {"diagnostics.probes=[[0.05]]", "diagnostics.probes=[0.05, 0.1]",
                          "diagnostics.probes=[[0.05, \"a\"]]", "diagnostics.probes=0.05"}) {
    e = error_of("[gas]\n", bad);
    EXPECT_NE(e.find("diagnostics.probes"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_EQ(error_of("[gas]\n", "diagnostics.probes=[[0.0, 0.9], [0.15, 0.0]]"), "");  // walls

  // The program: exit 2, one line that names the probe.
  const CommandResult r = run_fluidbed(
      "run " + std::string(FLUIDBED_ASSET_DIR) +
          "/scenes/xu_yu_1997.toml --set 'diagnostics.probes=[[0.075, 0.1], [0.16, 0.1]]'",
      "probe-outside");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("probe 2 at (0.16, 0.1) m outside the gas domain"), std::string::npos)
      << r.err;
  // The paper's scene has a probe of its own (0.075, 0.10): a bed made narrower than that is
  // told how to move or drop it.
  const CommandResult narrow = run_fluidbed(
      "check " + std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml --set domain.width=0.05 --set gas.cells_x=5",
      "probe-narrow");
  EXPECT_EQ(narrow.status, 2) << narrow.err;
  EXPECT_EQ(std::count(narrow.err.begin(), narrow.err.end(), '\n'), 1) << narrow.err;
  EXPECT_NE(narrow.err.find("probe 1 at (0.075, 0.1) m outside the gas domain (x in [0, 0.05] m"),
            std::string::npos)
      << narrow.err;
  EXPECT_NE(narrow.err.find("set diagnostics.probes = [] for none"), std::string::npos)
      << narrow.err;
}
