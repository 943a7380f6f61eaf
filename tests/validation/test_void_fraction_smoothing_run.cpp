// The smoothed void fraction in a coupled run (coupling.void_fraction = "smoothed"): the gas
// cells hold the same solid volume as with the exact shares, with smaller jumps from cell to
// cell; a run with it is the same bits on one and two threads, and the key reaches the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../test_support.hpp"
#include "coupling/coupler.hpp"
#include "run/run_loop.hpp"
#include "scene/scene_loader.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

const std::string kScene = small_jet_bed_toml("smoothing-test");
const std::vector<std::string> kSmoothed = {"coupling.void_fraction=\"smoothed\"",
                                            "coupling.void_fraction_length=0.01"};

std::uint64_t hash_after(Settings s, int threads, int steps) {
  s.threads = threads;
  Simulation sim(s);
  for (int k = 0; k < steps; ++k) sim.step();
  return sim.state_hash();
}

// m^3: the solid volume the field eps holds.
double solid_in(const GasGrid& g, const std::vector<double>& eps) {
  double v = 0.0;
  for (const double e : eps) v += (1.0 - e) * g.cell_volume();
  return v;
}

// The largest jump of eps between cells side by side across the width.
double largest_jump(const GasGrid& g, const std::vector<double>& eps) {
  double jump = 0.0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i + 1 < g.nx; ++i)
      jump = std::max(jump, std::fabs(eps[g.index(i + 1, j)] - eps[g.index(i, j)]));
  return jump;
}

}  // namespace

TEST(VoidFractionSmoothingRun, KeepsTheSolidAndEvensTheCells) {
  // The settled bed of the small jetted scene (0.12 s), its porosity taken both ways.
  Simulation sim(parse_scene(kScene, "smoothing.toml"));
  run_simulation(sim, RunOptions{});
  do sim.step();
  while (sim.steps_since_gas_step() != 0);  // the run's field is that of the particles now
  const GasGrid& g = sim.gas()->grid();
  const Particles& p = sim.dem().particles();
  double spheres = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    spheres += 4.0 / 3.0 * 3.141592653589793 * std::pow(p.radius[i], 3);
  CouplerParams exact_params, smooth_params;
  smooth_params.smoothing_length = 0.01;  // one cell across (10 mm), half a cell up (20 mm)
  Coupler exact(g, exact_params, p.size()), smooth(g, smooth_params, p.size());
  const std::vector<double> e0 = exact.compute_porosity(p, sim.time());
  const std::vector<double> e1 = smooth.compute_porosity(p, sim.time());
  EXPECT_NEAR(solid_in(g, e0), spheres, 1e-12 * spheres);
  EXPECT_NEAR(solid_in(g, e1), spheres, 1e-12 * spheres);
  EXPECT_EQ(e0, sim.coupler()->porosity());  // the run's own field is the exact one
  // The jet's channel through the packed layer makes a jump of about 0.2 between exact cells
  // side by side (0.21 measured); smoothing over a cell's width spreads it over about L (0.07).
  const double j0 = largest_jump(g, e0), j1 = largest_jump(g, e1);
  std::printf("largest jump of eps across the width: exact %.3f, smoothed over 1 cm %.3f\n", j0, j1);
  EXPECT_GT(j0, 0.1);
  EXPECT_LT(j1, 0.5 * j0);
}

TEST(VoidFractionSmoothingRun, SameBitsOnOneAndTwoThreadsAndTheKeyReachesTheRun) {
  const Settings exact = parse_scene(kScene, "smoothing.toml");
  const Settings smoothed = parse_scene(kScene, "smoothing.toml", kSmoothed);
  const std::uint64_t one = hash_after(smoothed, 1, 1500), two = hash_after(smoothed, 2, 1500);
  EXPECT_EQ(one, two);
  EXPECT_NE(one, hash_after(exact, 1, 1500));
  // The run's field is the smoothed one.
  Simulation sim(smoothed);
  for (int k = 0; k < 200 || sim.steps_since_gas_step() != 0; ++k) sim.step();
  CouplerParams smooth_params;
  smooth_params.smoothing_length = 0.01;
  Coupler again(sim.gas()->grid(), smooth_params, sim.particle_count());
  EXPECT_EQ(again.compute_porosity(sim.dem().particles(), sim.time()), sim.coupler()->porosity());
}
