// Contact scenarios with closed-form answers: a head-on collision of two equal spheres and a
// sphere that slides, then rolls, on a floor with friction.
#include <gtest/gtest.h>

#include <cmath>

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
