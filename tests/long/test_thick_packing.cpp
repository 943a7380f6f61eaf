// A thick slab packed in fluidbed and in LIGGGHTS: van Wachem's particles (assets/scenes/
// van_wachem_2001.toml, 1.545 mm, its linear contact, friction and rolling resistance), 4000 of
// them dropped from the random lattice (random depths) into a column 0.03 m wide and 0.008 m
// (5.2 diameters) deep, without gas, 0.7 s. The same start and walls in both codes (the export
// writes each sphere's z and the front and back walls of a thick slab).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "../liggghts_support.hpp"
#include "../test_support.hpp"
#include "analysis/packing_metrics.hpp"
#include "io/liggghts_export.hpp"
#include "run/run_loop.hpp"
#include "scene/scene_loader.hpp"
#include "sim/simulation.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

// The solid fraction of the spheres whose centres lie between 10 diameters above the floor and
// 10 below the bed's height (packing_metrics' height: the mean of the highest centre over
// columns 1 cm wide), over that band's volume. packing_metrics' own band (0.02 m to
// height - 0.03 m) is for the paper's 4 mm spheres; a bed of 1.5 mm spheres 5 cm high needs
// one that scales with them.
double band_solid_fraction(const Particles& p, const Settings& s, double& height) {
  height = measure_packing(p, s.domain.width, s.domain.thickness).bed_height;
  const double d = s.particles.diameter, lo = 10.0 * d, hi = height - 10.0 * d;
  double volume = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.y[i] >= lo && p.y[i] < hi) volume += std::numbers::pi * d * d * d / 6.0;
  return volume / (s.domain.width * s.domain.thickness * (hi - lo));
}

}  // namespace

TEST(ThickPacking, SolidFractionMatchesLiggghts) {
  REQUIRE_LIGGGHTS(binary);
  const Settings s = load_scene(
      std::string(FLUIDBED_ASSET_DIR) + "/scenes/van_wachem_2001.toml",
      {"scene.kind=packing", "particles.count=4000", "domain.width=0.03", "domain.height=0.34",
       "particles.placement=lattice", "gas.enabled=false", "diagnostics.probes=[]",
       "time.end=0.7"});  // no gas: the scene's pressure probe goes with it
  Simulation sim(s);
  ASSERT_TRUE(sim.dem().particles().has_depth());
  RunOptions opt;
  opt.until = s.time.end;
  run_simulation(sim, opt);
  double h_ours = 0.0, h_peer = 0.0;
  const double ours = band_solid_fraction(sim.dem().particles(), s, h_ours);

  const auto dir = temp_dir("thick-packing-liggghts");
  write_liggghts_case(s, dir.string());
  const LiggghtsRun r = run_liggghts(*binary, dir);
  ASSERT_EQ(r.status, 0) << r.log;
  const Particles p = read_liggghts_dump((dir / "final.dump").string(), s.particles.density);
  ASSERT_EQ(p.size(), 4000u);
  const double peer = band_solid_fraction(p, s, h_peer);
  std::printf("thick slab packed: fluidbed solid fraction %.4f, bed height %.4f m; LIGGGHTS "
              "%.4f, %.4f m (%.1f s wall)\n",
              ours, h_ours, peer, h_peer, r.wall_s);
  EXPECT_NEAR(ours, peer, 0.03 * peer);
  EXPECT_NEAR(h_ours, h_peer, 0.03 * h_peer);
}
