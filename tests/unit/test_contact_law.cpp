// Contact law (eqs 3-7, 13) against hand calculations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../test_support.hpp"
#include "dem/contact_law.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

using fluidbed::contact_force;
using fluidbed::ContactParams;
using fluidbed::damping_for_stiffness;
using fluidbed::restitution_from_damping;

namespace {
ContactParams paper() { return ContactParams{50000.0, 50000.0, 0.15, 0.15, 0.3}; }
}  // namespace

TEST(ContactLaw, NormalSpringPushesApart) {
  // delta_n = 1e-5 m at rest: f_n = -kappa_n delta_n = -0.5 N (towards -n, away from j).
  double ds = 0.0;
  const auto f = contact_force(paper(), 1e-5, ds, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(f.fn, -0.5);
  EXPECT_DOUBLE_EQ(f.ft, 0.0);
  EXPECT_FALSE(f.sliding);
}

TEST(ContactLaw, NormalDampingOpposesApproach) {
  // Approaching at v_n = 2 m/s with delta_n = 1e-5: -0.5 N spring, -0.15 * 2 = -0.3 N dashpot.
  double ds = 0.0;
  const auto f = contact_force(paper(), 1e-5, ds, 2.0, 0.0);
  EXPECT_NEAR(f.fn, -0.8, 1e-15);
  // Separating at 2 m/s: the dashpot pulls back (+0.3 N), the spring still pushes (-0.5 N).
  const auto g = contact_force(paper(), 1e-5, ds, -2.0, 0.0);
  EXPECT_NEAR(g.fn, -0.2, 1e-15);
}

TEST(ContactLaw, SpringActsInCompressionOnly) {
  double ds = 0.0;
  const auto f = contact_force(paper(), -1e-6, ds, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(f.fn, 0.0);
}

TEST(ContactLaw, TangentialSpringAndDampingBelowFrictionLimit) {
  // delta_n = 1e-4 (f_cn = 5 N, limit 1.5 N); delta_t = 1e-5 (f_ct = -0.5 N), v_t = 1 m/s
  // (dashpot -0.15 N): sticking, f_t = -0.65 N, delta_t unchanged.
  double ds = 1e-5;
  const auto f = contact_force(paper(), 1e-4, ds, 0.0, 1.0);
  EXPECT_FALSE(f.sliding);
  EXPECT_NEAR(f.ft, -0.65, 1e-15);
  EXPECT_DOUBLE_EQ(ds, 1e-5);
}

TEST(ContactLaw, FrictionCapKeepsSignAndHoldsSpringAtLimit) {
  // delta_n = 1e-5 (f_cn = 0.5 N, limit 0.15 N); delta_t = -4e-5 (f_ct = +2 N > limit): slides.
  double ds = -4e-5;
  const auto f = contact_force(paper(), 1e-5, ds, 0.0, -3.0);
  EXPECT_TRUE(f.sliding);
  EXPECT_NEAR(f.ft, 0.15, 1e-15);  // the sign of the spring force, no dashpot while sliding
  EXPECT_NEAR(ds, -0.15 / 50000.0, 1e-20);  // spring held at the Coulomb limit
  double dt2 = 4e-5;
  const auto g = contact_force(paper(), 1e-5, dt2, 0.0, 3.0);
  EXPECT_NEAR(g.ft, -0.15, 1e-15);
}

TEST(ContactLaw, FrictionlessContactHasNoTangentialSpringForceWhenSliding) {
  ContactParams p = paper();
  p.mu = 0.0;
  double ds = 1e-6;
  const auto f = contact_force(p, 1e-5, ds, 0.0, 1.0);
  EXPECT_TRUE(f.sliding);
  EXPECT_DOUBLE_EQ(f.ft, 0.0);
  EXPECT_DOUBLE_EQ(ds, 0.0);
}

TEST(ContactLaw, BackwardProjectedTouchTime) {
  // Eq 13: j at distance L = 3.9e-3 along x from i, approaching head on at 2 m/s (w = -2 x):
  // it touched (R = 4e-3) (R - L) / 2 = 5e-5 s ago.
  const double s = fluidbed::time_since_touch(3.9e-3, 0.0, -2.0, 0.0, 4e-3, 3.9e-3);
  EXPECT_NEAR(s, 5e-5, 1e-15);
  // Oblique: p = (0.003, 0.0025), w = (-1, 0). Hand solution of |p - w s| = R:
  // (0.003 + s)^2 + 0.0025^2 = 0.004^2 -> s = sqrt(0.004^2 - 0.0025^2) - 0.003.
  const double L = std::hypot(0.003, 0.0025);
  const double s2 = fluidbed::time_since_touch(0.003, 0.0025, -1.0, 0.0, 0.004, L);
  EXPECT_NEAR(s2, std::sqrt(0.004 * 0.004 - 0.0025 * 0.0025) - 0.003, 1e-15);
  // No relative motion: placed touching, no history to project.
  EXPECT_DOUBLE_EQ(fluidbed::time_since_touch(0.003, 0.0, 0.0, 0.0, 0.004, 0.003), 0.0);
  // Wall: 3e-6 m in, approaching at 1.5 m/s: touched 2e-6 s ago.
  EXPECT_NEAR(fluidbed::time_since_touch_wall(3e-6, 1.5), 2e-6, 1e-18);
  EXPECT_DOUBLE_EQ(fluidbed::time_since_touch_wall(3e-6, -1.0), 0.0);
}

TEST(ContactLaw, RollingTorqueOpposesRelativeRollingAndNeverReversesIt) {
  // mu_r = 0.1, R_r = 2e-3 m, |F_n| = 1 N: 2e-4 N m against w_rel, whatever the sign of F_n.
  EXPECT_NEAR(fluidbed::rolling_torque(0.1, 2e-3, -1.0, 50.0, 1e7, 1.5e-5), -2e-4, 1e-18);
  EXPECT_NEAR(fluidbed::rolling_torque(0.1, 2e-3, 1.0, -50.0, 1e7, 1.5e-5), 2e-4, 1e-18);
  EXPECT_DOUBLE_EQ(fluidbed::rolling_torque(0.1, 2e-3, 1.0, 0.0, 1e7, 1.5e-5), 0.0);
  // Slow relative rolling: 1 rad/s stops within a step of 1.5e-5 s under 1 / (1.5e-5 x 1e7)
  // = 6.67e-3 N m... but here k = 1e9 1/(kg m^2): the cap is 1 / (1.5e-5 x 1e9) = 6.67e-5 N m,
  // below 2e-4: the torque is the cap, which leaves w_rel at exactly 0 after the step.
  const double m = fluidbed::rolling_torque(0.1, 2e-3, 1.0, 1.0, 1e9, 1.5e-5);
  EXPECT_NEAR(m, -1.0 / (1.5e-5 * 1e9), 1e-18);
  EXPECT_NEAR(1.0 + m * 1e9 * 1.5e-5, 0.0, 1e-12);
}

TEST(ContactLaw, ThreeDimensionalLawInThePlaneIsThePlanarLaw) {
  // n in the x-y plane, the shear along t = z x n, the relative velocity in the plane: every
  // component of contact_force_3d is contact_force's, sticking and sliding.
  const ContactParams p = paper();
  const double a = 0.4;
  const fluidbed::Vec3 n{std::cos(a), std::sin(a), 0.0}, t{-std::sin(a), std::cos(a), 0.0};
  for (const double ds0 : {1e-7, 3e-5}) {  // sticks, then slides (|kt ds| > mu kn dn)
    const double dn = 1e-5, vn = 0.2, vt = -0.1, tau = 1e-6, h = 1.5e-5;
    double ds = ds0 + vt * tau;
    const auto f2 = fluidbed::contact_force(p, dn, ds, vn, vt);
    fluidbed::Vec3 s = ds0 * t;
    const auto f3 = fluidbed::contact_force_3d(p, dn, s, n, vn * n + vt * t, tau, h);
    EXPECT_EQ(f3.sliding, f2.sliding);
    EXPECT_NEAR(f3.force.x, f2.fn * n.x + f2.ft * t.x, 1e-15);
    EXPECT_NEAR(f3.force.y, f2.fn * n.y + f2.ft * t.y, 1e-15);
    EXPECT_EQ(f3.force.z, 0.0);
    EXPECT_NEAR(f3.lever.z, f2.ft, 1e-15);  // n x t = z
    EXPECT_NEAR(fluidbed::dot(s, t), ds, 1e-18);
  }
}

TEST(ContactLaw, ShearTurnsIntoTheContactPlaneAtItsLength) {
  // A shear of 2e-6 m along x while the normal has turned to (0.6, 0.8, 0): its normal part
  // (0.6 x 2e-6) is removed and the rest, (0.64, -0.48, 0) x 2e-6, scaled back to 2e-6 m:
  // (0.8, -0.6, 0) x 2e-6. With no relative motion and kt = 0 nothing else changes it.
  ContactParams p = paper();
  p.kt = 0.0;
  fluidbed::Vec3 s{2e-6, 0.0, 0.0};
  fluidbed::contact_force_3d(p, 1e-6, s, {0.6, 0.8, 0.0}, {}, 1e-6, 1e-6);
  EXPECT_NEAR(s.x, 0.8 * 2e-6, 1e-21);
  EXPECT_NEAR(s.y, -0.6 * 2e-6, 1e-21);
  EXPECT_DOUBLE_EQ(s.z, 0.0);
  // Sliding in 3D: the friction force is mu |F_n spring| along the spring, and the spring is
  // held there. kn = kt = 5e4 N/m, dn = 1e-5 m: limit 0.3 x 0.5 N = 0.15 N; shear (3, 0, 4)e-5 m
  // pulls with 2.5 N, beyond it: F_t = -0.15 N along (0.6, 0, 0.8), s = F_t / -kt = (1.8, 0,
  // 2.4)e-6 m. The normal (0, 1, 0) and no relative motion: F = (-0.09, -0.5, -0.12) N.
  const ContactParams q = paper();
  fluidbed::Vec3 s2{3e-5, 0.0, 4e-5};
  const auto f = fluidbed::contact_force_3d(q, 1e-5, s2, {0.0, 1.0, 0.0}, {}, 0.0, 1.5e-5);
  EXPECT_TRUE(f.sliding);
  EXPECT_NEAR(f.force.x, -0.09, 1e-15);
  EXPECT_NEAR(f.force.y, -0.5, 1e-15);
  EXPECT_NEAR(f.force.z, -0.12, 1e-15);
  EXPECT_NEAR(s2.x, 1.8e-6, 1e-20);
  EXPECT_NEAR(s2.z, 2.4e-6, 1e-20);
  // lever = n x F_t = (0, 1, 0) x (-0.09, 0, -0.12) = (-0.12, 0, 0.09)
  EXPECT_NEAR(f.lever.x, -0.12, 1e-15);
  EXPECT_NEAR(f.lever.z, 0.09, 1e-15);
}

TEST(ContactLaw, BackwardProjectedTouchTimeOffThePlane) {
  // Eq 13 in 3D: p = (0.003, 0, 0.0025), w = (-1, 0, 0): the same hand solution as in the plane
  // with the offset along z instead of y.
  const double L = std::hypot(0.003, 0.0025);
  const double s = fluidbed::time_since_touch(0.003, 0.0, -1.0, 0.0, 0.004, L, 0.0025, 0.0);
  EXPECT_NEAR(s, std::sqrt(0.004 * 0.004 - 0.0025 * 0.0025) - 0.003, 1e-15);
}

// The teaching scene's damping by hand: 0.15 kg/s at 50,000 N/m becomes 0.15 sqrt(0.2) =
// 0.0670820393249937 kg/s at 10,000 N/m, and the restitution of a sphere on a wall (m = 4/3 pi
// (2 mm)^3 2500 kg/m^3) is the same at both.
TEST(ContactLaw, DampingScaledWithStiffnessKeepsTheRestitution) {
  const double eta = damping_for_stiffness(0.15, 50000.0, 10000.0);
  EXPECT_NEAR(eta, 0.067082039324993681, 1e-16);
  const double m = 4.0 / 3.0 * std::numbers::pi * 0.002 * 0.002 * 0.002 * 2500.0;
  EXPECT_NEAR(restitution_from_damping(10000.0, eta, m), restitution_from_damping(50000.0, 0.15, m),
              1e-14);
  EXPECT_LT(restitution_from_damping(10000.0, 0.15, m), restitution_from_damping(50000.0, 0.15, m));
}

// Hertz-Mindlin for two of van Wachem's spheres (d = 1.545 mm, 1150 kg/m^3) of E = 1e7 Pa,
// nu = 0.3, e = 0.9, at an overlap of 1e-5 m, by hand:
//   Y* = 1e7 / (2 x 0.91) = 5.4945e6 Pa, G* = (1e7 / 2.6) / (2 x 1.7) = 1.1312e6 Pa;
//   R* = 3.8625e-4 m, m* = 1.1103e-6 kg, a = sqrt(R* dn) = 6.2149e-5 m;
//   kn = (4/3) Y* a = 455.3 N/m (force 4.553e-3 N), kt = 8 G* a = 562.4 N/m;
//   beta = ln 0.9 / sqrt(ln^2 0.9 + pi^2) = -0.033518;
//   eta_n = 2 sqrt(5/6) 0.033518 sqrt(2 Y* a m*) = 1.6852e-3 kg/s,
//   eta_t = 2 sqrt(5/6) 0.033518 sqrt(8 G* a m*) = 1.5293e-3 kg/s.
TEST(ContactLaw, HertzMindlinSpringsAndDashpotsFollowTheOverlap) {
  ContactParams p;
  p.mu = 0.3;
  p.mu_r = 0.025;
  fluidbed::set_hertz(p, 1.0e7, 0.3, 0.9);
  const double y_eff = 1.0e7 / (2.0 * 0.91), g_eff = 1.0e7 / 2.6 / 3.4;
  EXPECT_DOUBLE_EQ(p.hertz_kn, 4.0 / 3.0 * y_eff);
  EXPECT_DOUBLE_EQ(p.hertz_kt, 8.0 * g_eff);
  const double r = 0.5 * 1.545e-3, m = 1150.0 * std::numbers::pi * std::pow(1.545e-3, 3) / 6.0;
  const ContactParams c = fluidbed::hertz_params(p, 1e-5, 0.5 * r, 0.5 * m);
  EXPECT_NEAR(c.kn, 455.3, 0.1);
  EXPECT_NEAR(c.kn * 1e-5, 4.553e-3, 1e-6);  // (4/3) Y* sqrt(R*) dn^(3/2)
  EXPECT_NEAR(c.kt, 562.4, 0.1);
  EXPECT_NEAR(c.eta_n, 1.6852e-3, 1e-7);
  EXPECT_NEAR(c.eta_t, 1.5293e-3, 1e-7);
  EXPECT_EQ(c.mu, 0.3);  // friction and rolling resistance are the linear law's
  EXPECT_EQ(c.mu_r, 0.025);
  // Four times the overlap: springs twice as stiff (a ~ sqrt(dn)), dashpots sqrt(2) stronger.
  const ContactParams c4 = fluidbed::hertz_params(p, 4e-5, 0.5 * r, 0.5 * m);
  EXPECT_NEAR(c4.kn / c.kn, 2.0, 1e-12);
  EXPECT_NEAR(c4.eta_n / c.eta_n, std::sqrt(2.0), 1e-12);
  // Apart: nothing; elastic (e = 1): no dashpots.
  const ContactParams apart = fluidbed::hertz_params(p, -1e-6, 0.5 * r, 0.5 * m);
  EXPECT_EQ(apart.kn, 0.0);
  EXPECT_EQ(apart.eta_t, 0.0);
  ContactParams elastic;
  fluidbed::set_hertz(elastic, 1.0e7, 0.3, 1.0);
  EXPECT_EQ(fluidbed::hertz_params(elastic, 1e-5, 0.5 * r, 0.5 * m).eta_n, 0.0);
}

// Hertz's duration, for the pair above meeting at 0.5 m/s: the scene van_wachem_2001.toml's
// comment gives 1.33e-4 s (2.87 (m*^2 / (R* Y*^2 v))^(1/5)); it grows as v^(-1/5).
TEST(ContactLaw, HertzDurationIsJohnsonsClosedForm) {
  ContactParams p;
  fluidbed::set_hertz(p, 1.0e7, 0.3, 0.9);
  const double r = 0.5 * 1.545e-3, m = 1150.0 * std::numbers::pi * std::pow(1.545e-3, 3) / 6.0;
  const double t = fluidbed::hertz_contact_duration(p.hertz_kn, 0.5 * r, 0.5 * m, 0.5);
  EXPECT_NEAR(t, 1.3264e-4, 0.0001e-4);
  EXPECT_NEAR(fluidbed::hertz_contact_duration(p.hertz_kn, 0.5 * r, 0.5 * m, 16.0) / t,
              std::pow(32.0, -0.2), 1e-12);
}

// The law's keys: Hertz-Mindlin needs its three material values and a thick slab; the linear law
// refuses them (they would be silently ignored); the check reports Hertz's duration.
TEST(ContactLaw, HertzMindlinKeysAreCheckedInOneLine) {
  using fluidbed::testing::scene_error;
  const std::string thick = "[domain]\nthickness = 0.012\n";
  const std::vector<std::string> hertz = {"contact.law=hertz_mindlin", "contact.youngs_modulus=1e7",
                                          "contact.poisson_ratio=0.3", "contact.restitution=0.9"};
  EXPECT_EQ(scene_error(thick, hertz), "");
  EXPECT_NE(scene_error("", hertz).find("needs a thick slab"), std::string::npos);
  for (std::size_t k = 1; k < hertz.size(); ++k) {
    std::vector<std::string> missing = hertz;
    missing.erase(missing.begin() + static_cast<std::ptrdiff_t>(k));
    const std::string key = hertz[k].substr(0, hertz[k].find('='));
    EXPECT_EQ(scene_error(thick, missing), key + " is needed with contact.law = \"hertz_mindlin\"");
    EXPECT_EQ(scene_error(thick, {hertz[k]}).rfind(key + " is for contact.law", 0), 0u) << key;
  }
  EXPECT_NE(scene_error(thick, {"contact.law=hertz"}).find("expected one of: linear, hertz_mindlin"),
            std::string::npos);
  EXPECT_NE(scene_error(thick, {"contact.law=hertz_mindlin", "contact.youngs_modulus=1e7",
                                "contact.poisson_ratio=0.5", "contact.restitution=0.9"})
                .find("contact.poisson_ratio"),
            std::string::npos);
  const fluidbed::Settings s = fluidbed::parse_scene(thick, "t.toml", hertz);
  const fluidbed::SceneCheck c = fluidbed::check_scene(s);
  const double m = 2700.0 * std::numbers::pi * std::pow(0.004, 3) / 6.0;  // the default sphere
  ContactParams p;
  fluidbed::set_hertz(p, 1e7, 0.3, 0.9);
  EXPECT_DOUBLE_EQ(c.figures.contact_duration_wall,
                   fluidbed::hertz_contact_duration(p.hertz_kn, 0.002, m, 1.0));
  EXPECT_EQ(c.figures.restitution_pair, 0.9);
  EXPECT_NE(fluidbed::describe_check(s, c).find("Hertz at an impact of 1 m/s"), std::string::npos);
}
