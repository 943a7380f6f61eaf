// Contact scenarios with closed-form answers: a head-on collision of two equal spheres and a
// sphere that slides, then rolls, on a floor with friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../test_support.hpp"
#include "dem/dem_solver.hpp"
#include "sim/model_params.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

struct Collision {
  double momentum_before, momentum_after, restitution;
};

Collision head_on(double dt, const std::string& integrator, const std::string& displacement) {
  Settings s;
  s.physics.gravity = 0.0;
  s.time.dt = dt;
  s.time.integrator = parse_option<Integrator>("time.integrator", integrator);
  s.contact.displacement = parse_option<Displacement>("contact.displacement", displacement);
  s.domain.width = 0.2;
  s.domain.height = 0.2;
  // 1 mm apart, closing at 1 m/s; tilted line of centres to exercise both axes.
  const double c = std::cos(0.3), sn = std::sin(0.3), gap = 0.005;
  DemSolver dem(dem_params_for(s), make_particles({{0.1 - 0.5 * gap * c, 0.1 - 0.5 * gap * sn, 0.5 * c, 0.5 * sn, 0.0},
                                   {0.1 + 0.5 * gap * c, 0.1 + 0.5 * gap * sn, -0.5 * c, -0.5 * sn, 0.0}}));
  const Particles& p = dem.particles();
  auto momentum = [&] { return p.mass[0] * p.vx[0] + p.mass[1] * p.vx[1]; };
  auto closing = [&] { return (p.vx[0] - p.vx[1]) * c + (p.vy[0] - p.vy[1]) * sn; };
  const double m0 = momentum(), v0 = closing();
  const auto steps = static_cast<std::int64_t>(3e-3 / dt);  // 1 ms to touch, 0.1 ms of contact
  for (std::int64_t k = 0; k < steps; ++k) dem.step();
  return {m0, momentum(), -closing() / v0};
}

}  // namespace

TEST(Collision, HeadOnConservesMomentumAndGivesReducedMassRestitution) {
  const double e = analytic_restitution(50000.0, 0.15, 0.5 * paper_mass());
  for (const char* integrator : {"newmark", "velocity_verlet", "symplectic_euler"}) {
    for (const char* disp : {"incremental", "geometric"}) {
      const Collision fine = head_on(1.5e-7, integrator, disp);
      const double scale = paper_mass() * 0.5;
      EXPECT_NEAR(fine.momentum_after, fine.momentum_before, 1e-15 * scale) << integrator << disp;
      std::printf("%-17s %-11s dt 1.5e-7: e = %.5f (analytic, m/2: %.5f)\n", integrator, disp,
                  fine.restitution, e);
      EXPECT_NEAR(fine.restitution, e, 0.002) << integrator << " " << disp;
      const Collision coarse = head_on(1.5e-5, integrator, disp);
      EXPECT_NEAR(coarse.momentum_after, coarse.momentum_before, 1e-15 * scale);
    }
  }
}

TEST(Rolling, SlidingSphereEndsRollingAtFiveSevenths) {
  // Released touching the floor at 1 m/s without spin: friction slows it and spins it up until
  // its contact point stops slipping, at v = 5/7 v0 (angular momentum about the contact point).
  for (const char* integrator : {"newmark", "velocity_verlet", "symplectic_euler"}) {
    Settings s = single_particle(0.02, 0.002, 1.0, 0.0);
    s.domain.width = 1.0;
    s.time.integrator = parse_option<Integrator>("time.integrator", integrator);
    DemSolver dem(dem_params_for(s), make_particles({{0.02, 0.002, 1.0, 0.0, 0.0}}));
    const auto steps = static_cast<std::int64_t>(0.3 / s.time.dt);
    for (std::int64_t k = 0; k < steps; ++k) dem.step();
    const Particles& p = dem.particles();
    std::printf("%-17s v / v0 = %.5f, w r / v = %.5f\n", integrator, p.vx[0],
                -p.w[0] * p.radius[0] / p.vx[0]);
    EXPECT_NEAR(p.vx[0], 5.0 / 7.0, 0.02 * 5.0 / 7.0) << integrator;
    EXPECT_NEAR(-p.w[0] * p.radius[0], p.vx[0], 0.01 * p.vx[0]) << integrator;  // rolling
  }
}

TEST(Rolling, WallFrictionAloneSetsTheSlidingOnTheFloor) {
  // The sphere of SlidingSphereEndsRollingAtFiveSevenths, with the walls' own friction gamma_w:
  // the floor's friction slows it at gamma_w g and spins it up at 5 gamma_w g / (2 R), so it
  // rolls from t* = 2 v0 / (7 gamma_w g) on (closed form). The particles' friction plays no part.
  const double v0 = 1.0, r = 0.002;
  auto rolling_from = [&](double wall_mu, double* v_end, double* w_end) {
    Settings s = single_particle(0.02, r, v0, 0.0);
    s.domain.width = 1.0;
    s.contact.friction = 0.3;
    s.contact.wall_friction = wall_mu;
    DemSolver dem(dem_params_for(s), make_particles({{0.02, r, v0, 0.0, 0.0}}));
    const Particles& p = dem.particles();
    double t_roll = NAN;
    const auto steps = static_cast<std::int64_t>(0.5 / s.time.dt);
    for (std::int64_t k = 1; k <= steps; ++k) {
      dem.step();
      if (std::isnan(t_roll) && std::fabs(p.vx[0] + p.w[0] * r) < 1e-3 * p.vx[0])
        t_roll = static_cast<double>(k) * s.time.dt;
    }
    *v_end = p.vx[0];
    *w_end = p.w[0];
    return t_roll;
  };
  const double g = Settings{}.physics.gravity;
  for (double mu : {0.1, 0.2}) {
    double v = 0.0, w = 0.0;
    const double t = rolling_from(mu, &v, &w);
    const double closed = 2.0 * v0 / (7.0 * mu * g);
    std::printf("gamma_w %.1f: rolls from %.5f s (closed form %.5f s), v / v0 = %.5f\n", mu, t,
                closed, v / v0);
    EXPECT_NEAR(t, closed, 0.01 * closed) << mu;
    EXPECT_NEAR(v, 5.0 / 7.0 * v0, 0.02 * 5.0 / 7.0 * v0) << mu;
  }
  // Frictionless walls: no tangential force at all, whatever the particles' friction.
  double v = 0.0, w = 0.0;
  EXPECT_TRUE(std::isnan(rolling_from(0.0, &v, &w)));
  EXPECT_EQ(v, v0);
  EXPECT_EQ(w, 0.0);
}

TEST(Rolling, ResistanceStopsARollingSphereAtTheClosedFormDistance) {
  // Rolling without slip at v0 = 0.2 m/s on the floor with contact.rolling_friction = 0.1: the
  // torque mu_r R m g dissipates mu_r m g v, the rolling sphere's kinetic energy is 7/10 m v^2, so
  // it decelerates at 5/7 mu_r g and stops after 7 v0^2 / (10 mu_r g) = 28.5 mm, in 0.29 s. Its
  // spin does not turn over: the torque's limiter stops it at zero; what is left is the rocking
  // of the tangential spring unloading (measured 2e-3 rad/s, 4e-6 m/s at the rim).
  const double v0 = 0.2, mu_r = 0.1;
  for (const char* integrator : {"newmark", "velocity_verlet", "symplectic_euler"}) {
    Settings s = single_particle(0.02, 0.002, v0, 0.0);
    s.domain.width = 1.0;
    s.contact.rolling_friction = mu_r;
    s.time.integrator = parse_option<Integrator>("time.integrator", integrator);
    const double r = 0.002, g = s.physics.gravity;
    // At rest on the floor: the overlap that carries its weight.
    const double y0 = r - paper_mass() * g / s.contact.stiffness;
    DemSolver dem(dem_params_for(s), make_particles({{0.02, y0, v0, 0.0, -v0 / r}}));
    const auto steps = static_cast<std::int64_t>(0.6 / s.time.dt);
    double w_max = -1.0;  // the largest spin seen: rolling forward it is negative
    for (std::int64_t k = 0; k < steps; ++k) {
      dem.step();
      w_max = std::max(w_max, dem.particles().w[0]);
    }
    const Particles& p = dem.particles();
    const double distance = p.x[0] - 0.02, expected = 7.0 * v0 * v0 / (10.0 * mu_r * g);
    std::printf("%-17s rolled %.4f mm (closed form %.4f mm), v = %.2e m/s, largest spin %.2e rad/s\n",
                integrator, 1e3 * distance, 1e3 * expected, p.vx[0], w_max);
    EXPECT_NEAR(distance, expected, 0.01 * expected) << integrator;
    EXPECT_LT(std::fabs(p.vx[0]), 1e-3 * v0) << integrator;
    EXPECT_LE(w_max * r, 1e-4 * v0) << integrator;
  }
}
