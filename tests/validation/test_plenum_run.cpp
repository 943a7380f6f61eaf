// A bed over a plenum (inlet.plenum_height): the gas enters below the particles' floor and
// crosses it freely, so a jet spreads under the bed before it enters it; the plenum holds no
// particle; a run with one is the same bits on one and two threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../test_support.hpp"
#include "analysis/pressure_probe.hpp"
#include "scene/scene_loader.hpp"
#include "sim/simulation.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

// The small jetted bed of test_support.hpp (cells of 10 x 20 mm), with a plenum of two rows
// (4 cm, as Lethe's van Wachem example) and the grid grown by them, so the bed's cells stay;
// cells of dy high.
Settings plenum_bed(double plenum, std::vector<std::string> set = {}, double dy = 0.02) {
  const long rows = std::lround(0.3 / dy), plenum_rows = std::lround(plenum / dy);
  set.insert(set.end(), {"inlet.plenum_height=" + std::to_string(plenum),
                         "gas.cells_y=" + std::to_string(rows + plenum_rows)});
  return parse_scene(small_jet_bed_toml("plenum-test"), "plenum.toml", set);
}

// m/s: the fastest upward gas in the row whose lower edge is the floor (row `floor_row`).
double fastest_up_at_floor(const Simulation& sim, int floor_row) {
  const GasSolver& g = *sim.gas();
  double fastest = 0.0;
  for (int i = 0; i < g.grid().nx; ++i) {
    double ux = 0.0, uy = 0.0;
    g.cell_velocity(g.grid().index(i, floor_row), ux, uy);
    fastest = std::max(fastest, uy);
  }
  return fastest;
}

}  // namespace

TEST(PlenumRun, AFixedBedOverAPlenumKeepsItsPressureGradientAndTheJetSpreads) {
  // A fixed bed, the full lattice (925 spheres in rows 10 cm high) held in place, on cells of
  // 10 mm, blown uniformly at 1.5 m/s: inside the bed the pressure falls at the rate the bed's
  // drag sets, whether the gas enters at the floor or 4 cm below it.
  const std::vector<std::string> fixed = {"particles.frozen=true", "particles.fill_height=0.1",
                                          "particles.count=925", "inlet.kind=\"uniform\"",
                                          "inlet.superficial_velocity=1.5"};
  Simulation over(plenum_bed(0.04, fixed, 0.01)), on(plenum_bed(0.0, fixed, 0.01));
  for (int k = 0; k < 400; ++k) {
    over.step();
    on.step();
  }
  const auto gradient = [](const Simulation& sim) {  // Pa/m, from 3 to 7 cm up the centre line
    const GasSolver& g = *sim.gas();
    return (probe_pressure(g.grid(), g.pressure(), 0.075, 0.03) -
            probe_pressure(g.grid(), g.pressure(), 0.075, 0.07)) /
           0.04;
  };
  std::printf(
      "fixed bed at 1.5 m/s: -dp/dy inside it %.1f Pa/m over a 4 cm plenum, %.1f Pa/m "
      "without; dp %.2f and %.2f Pa\n",
      gradient(over), gradient(on), over.pressure_drop(), on.pressure_drop());
  EXPECT_GT(gradient(on), 1000.0);  // the bed resists (below U_mf: its weight is 13,700 Pa/m)
  EXPECT_NEAR(gradient(over), gradient(on), 0.02 * gradient(on));
  // The plenum holds no sphere: its cells' porosity is 1.
  const std::vector<double>& eps = over.gas()->porosity();
  for (int c = 0; c < 4 * over.gas()->grid().nx; ++c) EXPECT_EQ(eps[c], 1.0) << c;

  // The paper's jet through a settling bed: under the bed it has spread a little (a 1 cm slot
  // at 37.5 m/s keeps most of its speed over 4 cm of free gas).
  Simulation jet_over(plenum_bed(0.04)), jet_on(plenum_bed(0.0));
  for (int k = 0; k < 2000; ++k) {
    jet_over.step();
    jet_on.step();
  }
  const double spread = fastest_up_at_floor(jet_over, 2), direct = fastest_up_at_floor(jet_on, 0);
  std::printf(
      "fastest upward gas in the floor's row: %.2f m/s over a 4 cm plenum, %.2f m/s "
      "with the jet at the floor\n",
      spread, direct);
  EXPECT_LT(spread, direct);
  for (std::size_t i = 0; i < jet_over.particle_count(); ++i)
    ASSERT_GT(jet_over.dem().particles().y[i], 0.0) << i;
}

TEST(PlenumRun, SameBitsOnOneAndTwoThreads) {
  Settings s = plenum_bed(0.04);
  s.threads = 1;
  Simulation one(s);
  s.threads = 2;
  Simulation two(s);
  for (int k = 0; k < 1500; ++k) {
    one.step();
    two.step();
  }
  EXPECT_EQ(one.state_hash(), two.state_hash());
}

TEST(PlenumRun, ADistributorPlateDropsItsPressureInProportionAndSpreadsTheGas) {
  // The fixed bed of the first test over a 4 cm plenum, blown uniformly, with and without a
  // plate at the floor of 200 Pa s/m: at 1.5 m/s the plenum's pressure rises by 300 Pa, the
  // bed's does not move; at 0.75 m/s the plate drops 150 Pa (in proportion to the flow: Darcy's
  // law).
  const auto fixed = [](double plate) {
    return std::vector<std::string>{"particles.frozen=true",
                                    "particles.fill_height=0.1",
                                    "particles.count=925",
                                    "inlet.kind=\"uniform\"",
                                    "inlet.superficial_velocity=1.5",
                                    "inlet.distributor_resistance=" + std::to_string(plate),
                                    "gas.tolerance=1e-9"};
  };
  auto settle = [](Simulation& sim, double u) {
    sim.set_superficial_velocity(u);
    for (int k = 0; k < 400; ++k) sim.step();
  };
  auto p_at = [](const Simulation& sim, double y) {
    const GasSolver& g = *sim.gas();
    return probe_pressure(g.grid(), g.pressure(), 0.075, y);
  };
  for (const double u : {1.5, 0.75}) {
    Simulation plate(plenum_bed(0.04, fixed(200.0), 0.01)),
        free(plenum_bed(0.04, fixed(0.0), 0.01));
    settle(plate, u);
    settle(free, u);
    const double in_plenum = p_at(plate, -0.02) - p_at(free, -0.02);
    const double in_bed = p_at(plate, 0.05) - p_at(free, 0.05);
    const double bed = p_at(free, 0.05);
    std::printf(
        "U %.2f m/s: the plenum's pressure %.2f Pa above the free floor's (200 U = %.1f), "
        "the bed's %.3f Pa (of %.1f Pa)\n",
        u, in_plenum, 200.0 * u, in_bed, bed);
    EXPECT_NEAR(in_plenum, 200.0 * u, 0.01 * 200.0 * u) << u;
    EXPECT_NEAR(in_bed, 0.0, 0.01 * bed) << u;  // 1 %: the plate only adds below the floor
  }

  // The paper's jet into the fixed bed through a plate that drops 1200 Pa at the scene's U:
  // the gas crosses the floor spread over more columns than through the free floor.
  auto jetted = [&](double plate) {
    Simulation sim(
        plenum_bed(0.04,
                   {"particles.frozen=true", "particles.fill_height=0.1", "particles.count=925",
                    "inlet.distributor_resistance=" + std::to_string(plate)},
                   0.01));
    for (int k = 0; k < 400; ++k) sim.step();
    return fastest_up_at_floor(sim, 4) / sim.gas()->superficial_velocity();
  };
  const double u = plenum_bed(0.04).inlet.superficial_velocity;
  const double through_plate = jetted(1200.0 / u), through_free = jetted(0.0);
  std::printf(
      "the jet's fastest gas over the floor: %.2f U through the plate, %.2f U through "
      "the free floor\n",
      through_plate, through_free);
  EXPECT_LT(through_plate, 0.8 * through_free);
}
