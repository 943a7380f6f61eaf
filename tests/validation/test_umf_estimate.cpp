// The scene's own U_mf (run/umf_estimate.hpp), which the viewer's presets and slider scale use:
// the fixed-bed force balance crosses 1 there, it is cached, and a bed of lighter particles gets
// a lower U_mf, so lower preset velocities.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "../view/view_scene.hpp"
#include "core/errors.hpp"
#include "run/umf_estimate.hpp"
#include "view/presets.hpp"

using namespace fluidbed;

TEST(UmfEstimate, ForceBalanceCrossesOneAndLighterParticlesGetLowerPresets) {
  Settings heavy = fluidbed::testing::view_test_settings();  // 100 glass spheres of 2700 kg/m^3
  Settings light = heavy;
  light.particles.density = 1350.0;
  const UmfEstimate h = estimate_umf(heavy), l = estimate_umf(light);
  std::printf("U_mf: %.4f m/s at 2700 kg/m^3 (%d runs%s), %.4f m/s at 1350 (Wen-Yu %.4f, %.4f)\n",
              h.umf, h.evaluations, h.from_cache ? ", cached" : "", l.umf, h.wen_yu, l.wen_yu);
  // The root: the fluid force on the fixed bed equals its weight within 1 %, and is on either
  // side of it 5 % away.
  const Settings fixed = fixed_bed_settings(heavy);
  EXPECT_NEAR(fixed_bed_lift(fixed, h.umf), 1.0, 0.01);
  EXPECT_LT(fixed_bed_lift(fixed, 0.95 * h.umf), 1.0);
  EXPECT_GT(fixed_bed_lift(fixed, 1.05 * h.umf), 1.0);
  // Half the density, half the weight to carry: U_mf falls between the viscous limit (the drag
  // linear in U: a half) and the inertial one (quadratic: 1 / sqrt(2) = 0.71); at these Reynolds
  // numbers it is near the inertial one.
  EXPECT_LT(l.umf, 0.75 * h.umf);
  EXPECT_GT(l.umf, 0.4 * h.umf);
  for (const app::Preset& p : app::kPresets)
    EXPECT_LT(p.umf_multiple * l.umf, p.umf_multiple * h.umf) << p.name;
  // Asked again: the cache answers, with the same number.
  const UmfEstimate again = estimate_umf(heavy);
  EXPECT_TRUE(again.from_cache);
  EXPECT_EQ(again.evaluations, 0);
  EXPECT_NEAR(again.umf, h.umf, 1e-6 * h.umf);
  EXPECT_TRUE(std::filesystem::exists(again.cache_file));
  // A scene without gas has none.
  Settings no_gas = heavy;
  no_gas.gas.enabled = false;
  EXPECT_THROW(estimate_umf(no_gas), InputError);
}
