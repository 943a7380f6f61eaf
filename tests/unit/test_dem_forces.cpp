// Pair and wall contact forces and torques inside the solver, against hand calculations.
// Symplectic Euler evaluates the forces at the initial state, so one step exposes them.
#include <gtest/gtest.h>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "dem/dem_solver.hpp"
#include "sim/model_params.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

Settings force_probe(Displacement displacement) {
  Settings s;
  s.physics.gravity = 0.0;
  s.time.integrator = Integrator::SymplecticEuler;
  s.contact.displacement = displacement;
  s.domain.width = 0.1;
  s.domain.height = 0.1;
  return s;
}

}  // namespace

TEST(DemForces, PairContactGeometricOverlap) {
  // Overlap 1e-5 m along x; v_i = (0.1, 0.05), spins 3 and -1 rad/s.
  // n = +x, t = +y; v_n = 0.1; v_t = 0.05 + 3 * 0.002 + (-1) * 0.002 = 0.054 m/s.
  // f_n = -5e4 * 1e-5 - 0.15 * 0.1 = -0.515 N.
  // delta_t = 0.054 * 1.5e-5 = 8.1e-7 m: f_t = -5e4 * 8.1e-7 - 0.15 * 0.054 = -0.0486 N
  // (below the limit 0.3 * 0.5 = 0.15 N). Torque on both: 0.002 * -0.0486 N m.
  DemSolver dem(dem_params_for(force_probe(Displacement::Geometric)),
                make_particles({{0.05, 0.05, 0.1, 0.05, 3.0}, {0.05 + 0.004 - 1e-5, 0.05, 0.0, 0.0, -1.0}}));
  dem.step();
  const Particles& p = dem.particles();
  EXPECT_NEAR(p.fx[0], -0.515, 1e-9);
  EXPECT_NEAR(p.fy[0], -0.0486, 1e-9);
  EXPECT_NEAR(p.fx[1], 0.515, 1e-9);
  EXPECT_NEAR(p.fy[1], 0.0486, 1e-9);
  EXPECT_NEAR(p.torque[0], 0.002 * -0.0486, 1e-12);
  EXPECT_NEAR(p.torque[1], 0.002 * -0.0486, 1e-12);
  EXPECT_EQ(dem.diagnostics().pair_contacts, 1);
  EXPECT_NEAR(dem.diagnostics().max_overlap_ratio, 1e-5 / 0.004, 1e-9);
}

TEST(DemForces, PairContactIncrementalFirstStep) {
  // Eqs 13-14: a new contact's normal displacement is v_n times the time since touching, capped
  // at one step. Overlap 1e-7 m closing at 0.1 m/s: touched 1e-6 s ago (< dt): delta_n = 1e-7,
  // f_n = -5e4 * 1e-7 - 0.15 * 0.1 = -0.02 N.
  DemSolver a(dem_params_for(force_probe(Displacement::Incremental)),
              make_particles({{0.05, 0.05, 0.1, 0.0, 0.0}, {0.05 + 0.004 - 1e-7, 0.05, 0.0, 0.0, 0.0}}));
  a.step();
  EXPECT_NEAR(a.particles().fx[0], -0.02, 1e-9);
  // Overlap 1e-5 m at 0.1 m/s: touched 1e-4 s ago (> dt): delta_n = 0.1 * 1.5e-5 = 1.5e-6 m,
  // f_n = -0.075 - 0.015 = -0.09 N, far less than the geometric 0.515 N.
  DemSolver b(dem_params_for(force_probe(Displacement::Incremental)),
              make_particles({{0.05, 0.05, 0.1, 0.0, 0.0}, {0.05 + 0.004 - 1e-5, 0.05, 0.0, 0.0, 0.0}}));
  b.step();
  EXPECT_NEAR(b.particles().fx[0], -0.09, 1e-9);
}

TEST(DemForces, WallContactForceAndTorque) {
  // 1e-5 m into the floor, falling at 0.1 m/s, sliding at 0.05 m/s, spin 3 rad/s.
  // n = -y (into the wall), t = z x n = +x. v_n = 0.1; v_t = 0.05 + 3 * 0.002 = 0.056.
  // f_n = -0.5 - 0.015 = -0.515 along n: +0.515 N up. delta_t = 0.056 * 1.5e-5 = 8.4e-7:
  // f_t = -0.042 - 0.0084 = -0.0504 N along +x. Torque 0.002 * -0.0504.
  DemSolver dem(dem_params_for(force_probe(Displacement::Geometric)), make_particles({{0.05, 0.002 - 1e-5, 0.05, -0.1, 3.0}}));
  dem.step();
  const Particles& p = dem.particles();
  EXPECT_NEAR(p.fy[0], 0.515, 1e-9);
  EXPECT_NEAR(p.fx[0], -0.0504, 1e-9);
  EXPECT_NEAR(p.torque[0], 0.002 * -0.0504, 1e-12);
  EXPECT_EQ(dem.diagnostics().wall_contacts, 1);
}

TEST(DemForces, WallFrictionSlidesAtCoulombLimit) {
  // Same, sliding fast (2 m/s): delta_t = 3e-5 m, spring 1.5 N > 0.3 * 0.5 N: f_t = -0.15 N.
  DemSolver dem(dem_params_for(force_probe(Displacement::Geometric)), make_particles({{0.05, 0.002 - 1e-5, 2.0, 0.0, 0.0}}));
  dem.step();
  EXPECT_NEAR(dem.particles().fx[0], -0.15, 1e-12);
  EXPECT_NEAR(dem.particles().fy[0], 0.5, 1e-9);
  EXPECT_EQ(dem.diagnostics().sliding_contacts, 1);
}

TEST(DemForces, RightAndLeftWallsPushInward) {
  DemSolver dem(dem_params_for(force_probe(Displacement::Geometric)),
                make_particles({{0.002 - 2e-6, 0.05, 0.0, 0.0, 0.0}, {0.1 - 0.002 + 2e-6, 0.05, 0.0, 0.0, 0.0}}));
  dem.step();
  EXPECT_NEAR(dem.particles().fx[0], 0.1, 1e-9);
  EXPECT_NEAR(dem.particles().fx[1], -0.1, 1e-9);
}

TEST(DemForces, RunawayOverlapIsReportedInWords) {
  // Two spheres driven into each other at 100 m/s: the step must fail, not carry on.
  Settings s = force_probe(Displacement::Geometric);
  DemSolver dem(dem_params_for(s), make_particles({{0.05, 0.05, 100.0, 0.0, 0.0}, {0.054, 0.05, -100.0, 0.0, 0.0}}));
  try {
    for (int k = 0; k < 10; ++k) dem.step();
    FAIL() << "no failure reported";
  } catch (const SimulationFailure& e) {
    EXPECT_NE(std::string(e.what()).find("overlap"), std::string::npos) << e.what();
  }
}
