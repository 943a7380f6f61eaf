// A plenum under the particles' floor (inlet.plenum_height): the gas grid reaches below y = 0,
// and everything that places a particle or a point on it (the cell of a centre, a sphere's
// volume shares, a probe) finds the same cell and the same values as on a grid without a plenum
// with the particles raised by its height; the key refused where it cannot be honoured.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../test_support.hpp"
#include "analysis/pressure_probe.hpp"
#include "cfd/gas_grid.hpp"
#include "core/errors.hpp"
#include "coupling/porosity.hpp"
#include "io/openfoam_export.hpp"
#include "scene/scene_loader.hpp"
#include "run/packed_bed.hpp"
#include "sim/model_params.hpp"

using namespace fluidbed;

namespace {

// 5 x 12 cells of 10 x 10 mm over 0.05 x 0.12 m; with a plenum of two cells the particles' floor
// is 20 mm above the grid's bottom.
GasGrid plenum_grid(double plenum) {
  GasGrid g;
  g.nx = 5;
  g.ny = 12;
  g.width = 0.05;
  g.height = 0.12;
  g.bottom = -plenum;
  return g;
}

}  // namespace

TEST(Plenum, CellsAndSharesAreThoseOfTheRaisedParticles) {
  // Shifting by 20 mm is exact in binary only approximately, so the shares are compared to
  // round-off, the cells exactly.
  const GasGrid with = plenum_grid(0.02), without = plenum_grid(0.0);
  EXPECT_EQ(with.row(-0.015), 0);  // inside the plenum
  EXPECT_EQ(with.row(0.001), 2);   // just above the floor: the third row
  EXPECT_EQ(without.row(0.021), 2);
  const double R = 0.002;
  // On the floor (straddling the line y = 0 between the plenum and the bed: a small overlap
  // into the floor goes to the plenum's top row), across a corner, inside one cell.
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {0.025, 0.0015}, {0.0195, 0.0305}, {0.034, 0.055}}) {
    VolumeShares a, b;
    const int na = particle_volume_shares(with, x, y, R, a);
    const int nb = particle_volume_shares(without, x, y + 0.02, R, b);
    ASSERT_EQ(na, nb) << x << ", " << y;
    for (int k = 0; k < na; ++k) {
      EXPECT_EQ(a.cell[k], b.cell[k]) << x << ", " << y;
      EXPECT_NEAR(a.volume[k], b.volume[k], 1e-12 * (4.0 / 3.0) * 3.1416 * R * R * R);
    }
    // The vectorised path gives the scalar path's shares on the grid with a plenum.
    ShareGeometry geo;
    geo.resize(1);
    share_geometry(with, 1, &x, &y, &R, geo);
    VolumeShares c;
    ASSERT_EQ(shares_from_geometry(with, geo, 0, R, c), na);
    for (int k = 0; k < na; ++k) {
      EXPECT_EQ(c.cell[k], a.cell[k]);
      EXPECT_EQ(c.volume[k], a.volume[k]);
    }
  }
  // The floor straddled: two shares, the lower in the plenum's top row (row 1).
  VolumeShares floor;
  ASSERT_EQ(particle_volume_shares(with, 0.025, 0.0015, R, floor), 2);
  EXPECT_EQ(floor.cell[0], with.index(2, 1));
}

TEST(Plenum, ProbesMeasureFromTheFloor) {
  const GasGrid with = plenum_grid(0.02), without = plenum_grid(0.0);
  std::vector<double> p(60);
  for (int c = 0; c < 60; ++c) p[static_cast<std::size_t>(c)] = 1000.0 - 7.0 * c + 0.5 * (c % 5) * (c % 5);
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {0.012, -0.013}, {0.025, 0.0}, {0.041, 0.045}}) {
    EXPECT_NEAR(probe_pressure(with, p, x, y), probe_pressure(without, p, x, y + 0.02), 1e-9)
        << x << ", " << y;
  }
}

TEST(Plenum, TheSceneKeyExtendsTheGasGridBelowTheFloor) {
  const Settings s =
      parse_scene("[gas]\ncells_y = 47\n", "t.toml", {"inlet.plenum_height=0.04"});
  const GasGrid g = gas_grid_for(s);
  EXPECT_DOUBLE_EQ(g.bottom, -0.04);
  EXPECT_DOUBLE_EQ(g.height, 0.94);  // the paper's 0.9 m and the plenum
  EXPECT_DOUBLE_EQ(g.dy(), 0.02);
  // Without a plenum the grid is the bed's, from the floor.
  const GasGrid plain = gas_grid_for(parse_scene("[gas]\n", "t.toml"));
  EXPECT_EQ(plain.bottom, 0.0);
  EXPECT_EQ(plain.height, 0.9);
  // A probe may stand in the plenum, not under it.
  EXPECT_EQ(fluidbed::testing::scene_error(
                "[gas]\n", {"inlet.plenum_height=0.04", "diagnostics.probes=[[0.075, -0.03]]"}),
            "");
  EXPECT_NE(fluidbed::testing::scene_error(
                "[gas]\n", {"inlet.plenum_height=0.04", "diagnostics.probes=[[0.075, -0.05]]"})
                .find("y in [-0.04, 0.9] m"),
            std::string::npos);
  // Without gas a plenum means nothing and is left alone: a scene with one runs with its gas
  // switched off (the thick packing test does so with van Wachem's scene).
  EXPECT_EQ(fluidbed::testing::scene_error("", {"inlet.plenum_height=0.04"}), "");
  EXPECT_NE(fluidbed::testing::scene_error("[gas]\n", {"inlet.plenum_height=-0.01"})
                .find("inlet.plenum_height"),
            std::string::npos);
}

// The distributor plate: its resistance on the row of faces the floor lies on; refused without a
// plenum or with the floor inside a cell.
TEST(Plenum, TheDistributorPlateSitsOnTheFloorsFaces) {
  using fluidbed::testing::scene_error;
  const Settings s = parse_scene("[gas]\ncells_y = 47\n", "t.toml",
                                 {"inlet.plenum_height=0.04", "inlet.distributor_resistance=400"});
  const GasParams p = fluidbed::gas_params_for(s);
  EXPECT_EQ(p.plate_row, 2);  // 0.04 m of 0.02 m cells
  EXPECT_DOUBLE_EQ(p.plate_resistance, 400.0);
  EXPECT_EQ(fluidbed::gas_params_for(parse_scene("[gas]\n", "t.toml")).plate_resistance, 0.0);
  EXPECT_NE(scene_error("[gas]\n", {"inlet.distributor_resistance=400"}).find("needs a plenum"),
            std::string::npos);
  EXPECT_NE(scene_error("[gas]\ncells_y = 47\n",
                        {"inlet.plenum_height=0.03", "inlet.distributor_resistance=400"})
                .find("a whole number of cells"),
            std::string::npos);
  // The packing beneath the bed is the same with or without a plate (no gas crosses its floor).
  EXPECT_EQ(fluidbed::packing_settings_for(s).inlet.distributor_resistance, 0.0);
}

TEST(Plenum, TheDpmFoamExportRefusesIt) {
  // The case's mesh starts at the particles' floor: a plenum is refused by name, not dropped.
  const Settings s = parse_scene("[gas]\n", "t.toml", {"inlet.plenum_height=0.04"});
  try {
    write_openfoam_case(s, "/nonexistent-plenum-case");
    FAIL() << "exported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inlet.plenum_height"), std::string::npos) << e.what();
  }
}
