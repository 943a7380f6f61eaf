// The scene's own U_mf (run/umf_estimate.hpp), which the viewer's presets, slider scale and
// lessons use: the decreasing branch of the scene's own sweep, fitted as `fluidbed sweep` fits
// it, cached; a bed of lighter particles gets a lower U_mf, so lower preset velocities; the
// fixed-bed force balance that stands in when a branch gives none crosses 1 at its root.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "../view/view_scene.hpp"
#include "analysis/umf_fit.hpp"
#include "core/errors.hpp"
#include "run/packed_bed.hpp"
#include "run/umf_estimate.hpp"
#include "run/velocity_sweep.hpp"
#include "scene/scene_loader.hpp"
#include "view/presets.hpp"

using namespace fluidbed;

TEST(UmfEstimate, TheSweepsWayDownAndLighterParticlesGetLowerPresets) {
  Settings heavy = fluidbed::testing::view_test_settings();  // 100 glass spheres of 2700 kg/m^3
  Settings light = heavy;
  light.particles.density = 1350.0;
  const UmfEstimate h = estimate_umf(heavy), l = estimate_umf(light);
  std::printf("U_mf: %.4f m/s at 2700 kg/m^3 (%d runs%s, %s), %.4f m/s at 1350 (%s; Wen-Yu %.4f, "
              "%.4f)\n",
              h.umf, h.evaluations, h.from_cache ? ", cached" : "", h.method().c_str(), l.umf,
              l.method().c_str(), h.wen_yu, l.wen_yu);
  // Both from the way down: the scene's decreasing-branch velocities (the heavy bed's are the
  // paper's list, its particles being the paper's), every run finished, and U_mf is the sweep's
  // fit of exactly those points.
  for (const UmfEstimate* e : {&h, &l}) {
    ASSERT_TRUE(e->from_sweep) << e->method();
    EXPECT_EQ(e->u.size(), e->dp.size());
    const UmfFit fit = fit_umf(e->u, e->dp);
    ASSERT_TRUE(fit.ok) << fit.why;
    EXPECT_NEAR(fit.umf, e->umf, 1e-5 * e->umf);  // the cache keeps 6 digits
  }
  EXPECT_EQ(h.u, decreasing_branch_velocities());
  EXPECT_EQ(l.u, decreasing_branch_velocities(light));
  // Half the density, half the weight to carry: U_mf falls, between the viscous limit (the drag
  // linear in U: a half) and the inertial one (quadratic: 1 / sqrt(2) = 0.71), within the
  // branches' resolution (their velocities are Wen and Yu's ratio apart).
  EXPECT_LT(l.umf, 0.85 * h.umf);
  EXPECT_GT(l.umf, 0.4 * h.umf);
  for (const app::Preset& p : app::kPresets)
    EXPECT_LT(p.umf_multiple * l.umf, p.umf_multiple * h.umf) << p.name;
  // Asked again: the cache answers, with the same number and branch.
  const UmfEstimate again = estimate_umf(heavy);
  EXPECT_TRUE(again.from_cache);
  EXPECT_TRUE(again.from_sweep);
  EXPECT_EQ(again.evaluations, 0);
  EXPECT_NEAR(again.umf, h.umf, 1e-6 * h.umf);
  EXPECT_EQ(again.u, h.u);
  EXPECT_TRUE(std::filesystem::exists(again.cache_file));
  // A folder of shipped answers is read when the cache has none: the same file, moved there.
  const auto shipped = std::filesystem::temp_directory_path() / "fluidbed_umf_shipped";
  std::filesystem::remove_all(shipped);
  std::filesystem::create_directories(shipped);
  std::filesystem::copy_file(again.cache_file, shipped / umf_cache_name(heavy));
  std::filesystem::remove(again.cache_file);
  const UmfEstimate from_shipped = estimate_umf(heavy, {}, shipped.string());
  EXPECT_TRUE(from_shipped.from_cache);
  EXPECT_EQ(from_shipped.cache_file, (shipped / umf_cache_name(heavy)).string());
  EXPECT_NEAR(from_shipped.umf, h.umf, 1e-6 * h.umf);
  std::filesystem::copy_file(shipped / umf_cache_name(heavy), again.cache_file);
  // What names the scene, its velocity and its end do not decide U_mf: the same answer.
  Settings renamed = heavy;
  renamed.scene.name = "another";
  renamed.inlet.superficial_velocity = 0.7;
  renamed.time.end = 9.0;
  EXPECT_EQ(umf_cache_name(renamed), umf_cache_name(heavy));
  // A scene without gas has none.
  Settings no_gas = heavy;
  no_gas.gas.enabled = false;
  EXPECT_THROW(estimate_umf(no_gas), InputError);
}

TEST(UmfEstimate, ForceBalanceCrossesOneAtItsRoot) {
  // What stands in for a bed whose way down has no plateau: the fluid force on the fixed bed
  // equals its weight within 1 % at the root, and is on either side of it 5 % away.
  const Settings heavy = fluidbed::testing::view_test_settings();
  int runs = 0;
  const double umf = force_balance_umf(heavy, 1.77, runs);
  const Settings fixed = fixed_bed_settings(heavy);
  EXPECT_GT(runs, 2);
  EXPECT_NEAR(fixed_bed_lift(fixed, umf), 1.0, 0.01);
  EXPECT_LT(fixed_bed_lift(fixed, 0.95 * umf), 1.0);
  EXPECT_GT(fixed_bed_lift(fixed, 1.05 * umf), 1.0);
}

TEST(UmfEstimate, ShippedScenesHaveTheirAnswersShipped) {
  // assets/umf holds the answers of the shipped beds the viewer opens, so that a class does not
  // wait for eight runs at the first start: each the file estimate_umf would write for the scene
  // as it is now (its name is the hash of everything that decides U_mf), from the way down, its
  // points refitting to its U_mf. When a scene or the model changes, this fails until the answer
  // is measured again (`fluidbed view SCENE --umf` and the file it names copied into
  // assets/umf/); and every file there belongs to one of these scenes.
  const std::filesystem::path shipped = std::filesystem::path(FLUIDBED_ASSET_DIR) / "umf";
  std::set<std::string> names;
  for (const char* scene : {"teaching.toml", "xu_yu_1997.toml"}) {
    const Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/" + scene);
    const std::string name = umf_cache_name(s);
    names.insert(name);
    const std::filesystem::path file = shipped / name;
    ASSERT_TRUE(std::filesystem::exists(file))
        << scene << ": no shipped answer " << file << "; measure it with `fluidbed view "
        << "assets/scenes/" << scene << " --umf` and copy the file it names into assets/umf/";
    UmfEstimate e;
    ASSERT_TRUE(read_umf_answer(file.string(), e)) << file;
    ASSERT_TRUE(e.from_sweep) << scene;
    EXPECT_EQ(e.u, decreasing_branch_velocities(s)) << scene;
    const UmfFit fit = fit_umf(e.u, e.dp);
    ASSERT_TRUE(fit.ok) << scene << ": " << fit.why;
    EXPECT_NEAR(fit.umf, e.umf, 1e-5 * e.umf) << scene;
  }
  for (const auto& f : std::filesystem::directory_iterator(shipped))
    EXPECT_TRUE(names.count(f.path().filename().string()))
        << f.path() << " is no shipped scene's answer: measured for settings no longer shipped";
}
