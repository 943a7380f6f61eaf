// The paper's packing (section 3, Fig. 5) against LIGGGHTS and LAMMPS with the same particles,
// contact law and start (5 seeds: bed height 0.232-0.236 m, solid fraction 0.563-0.575).
#include <gtest/gtest.h>

#include "../test_support.hpp"
#include "scene/scene_loader.hpp"
#include "run/run_loop.hpp"

using namespace fluidbed;

TEST(Packing, SettlesToThePeersBed) {
  const Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/packing.toml");
  Simulation sim(s);
  const RunResult r = run_simulation(sim, RunOptions{});
  const auto& j = r.summary;
  const double ke_peak = j["kinetic_energy_peak_j"].get<double>();
  const double ke_end = j["kinetic_energy_final_j"].get<double>();
  const double h = j["bed_height_m"].get<double>(), phi = j["solid_fraction"].get<double>();
  std::printf("packing: bed height %.4f m, solid fraction %.4f, KE end / peak %.2e, "
              "overlap now %.3f %%, %.3g particle-steps/s\n", h, phi, ke_end / ke_peak,
              100.0 * j["max_overlap_ratio_final"].get<double>(),
              j["particle_steps_per_s"].get<double>());
  EXPECT_LT(ke_end, 1e-3 * ke_peak);
  EXPECT_LT(j["max_overlap_ratio_final"].get<double>(), 0.01);
  const Particles& p = sim.dem().particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_GE(p.x[i] - p.radius[i], -0.01 * p.radius[i]);
    ASSERT_LE(p.x[i] + p.radius[i], s.domain.width + 0.01 * p.radius[i]);
    ASSERT_GE(p.y[i] - p.radius[i], -0.01 * p.radius[i]);
    ASSERT_LE(p.y[i] + p.radius[i], s.domain.height);
  }
  EXPECT_NEAR(h, 0.234, 0.03 * 0.234);
  EXPECT_NEAR(phi, 0.568, 0.03 * 0.568);
}
