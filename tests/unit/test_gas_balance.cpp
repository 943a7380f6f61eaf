// The gas solver's balances against hand calculations: hydrostatics, a uniform interaction force
// (Newton's third law on the faces, and the pressure that holds it), continuity with a porosity
// that changes in time.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cfd/gas_solver.hpp"

using namespace fluidbed;

namespace {

constexpr double kDt = 1.5e-5;  // s, the paper's step

GasParams closed_box() {
  GasParams p;
  p.inlet = InletKind::None;
  return p;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Sets the pressure to 0 everywhere so that a step has to find the balance itself.
void zero_pressure(GasSolver& gas) {
  GasState s = gas.state();
  std::fill(s.p.begin(), s.p.end(), 0.0);
  gas.set_state(s);
}

}  // namespace

TEST(GasHydrostatics, ClosedBoxAtRestFromZeroPressure) {
  const GasGrid g;
  GasSolver gas(g, closed_box());
  zero_pressure(gas);
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  for (int k = 0; k < 3; ++k) {
    const GasStepReport rep = gas.step(kDt, eps, zero, zero);
    EXPECT_TRUE(rep.converged) << "step " << k << ": residual " << rep.mass_residual;
  }
  const double rho_g_H = 1.205 * 9.81 * g.height;  // 10.639 Pa
  EXPECT_NEAR(gas.pressure_drop(), rho_g_H, 1e-6 * rho_g_H);
  for (int i = 0; i < g.nx; ++i) EXPECT_NEAR(gas.bottom_pressure(i), rho_g_H, 1e-6 * rho_g_H);
  EXPECT_LT(max_abs(gas.u()), 1e-12);
  EXPECT_LT(max_abs(gas.v()), 1e-12);
  // grad p = rho g down, in every cell (walls and exit included).
  for (int c = 0; c < g.cells(); ++c) {
    double gx, gy;
    gas.pressure_gradient(c, gx, gy);
    EXPECT_NEAR(gx, 0.0, 1e-9);
    EXPECT_NEAR(gy, -1.205 * 9.81, 1e-6 * 1.205 * 9.81) << "cell " << c;
  }
}

TEST(GasHydrostatics, NonUniformPorosityAtRestStaysHydrostatic) {
  // -eps grad p + rho eps g = 0 holds for any eps: the pressure does not see the porosity.
  const GasGrid g;
  GasSolver gas(g, closed_box());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.35, 1.0);
  std::vector<double> eps(g.cells());
  for (double& e : eps) e = U(rng);
  gas.set_porosity(eps);
  zero_pressure(gas);
  const std::vector<double> zero(g.cells(), 0.0);
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(gas.step(kDt, eps, zero, zero).converged);
  const double rho_g_H = 1.205 * 9.81 * g.height;
  EXPECT_NEAR(gas.pressure_drop(), rho_g_H, 1e-6 * rho_g_H);
  EXPECT_LT(max_abs(gas.u()), 1e-12);
  EXPECT_LT(max_abs(gas.v()), 1e-12);
}

TEST(GasForce, TotalOnTheGasIsSumOfCellForcesIncludingWallCells) {
  // A different F in every cell, wall cells included: the faces share it out exactly.
  const GasGrid g;
  GasSolver gas(g, closed_box());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-2e4, 2e4);
  std::vector<double> fx(g.cells()), fy(g.cells());
  double sx = 0.0, sy = 0.0;
  for (int c = 0; c < g.cells(); ++c) {
    fx[c] = U(rng);
    fy[c] = U(rng) + 2e4;
    sx += fx[c] * g.cell_volume();
    sy += fy[c] * g.cell_volume();
  }
  const std::vector<double> eps(g.cells(), 1.0);
  gas.step(kDt, eps, fx, fy);
  double gx, gy, wx, wy;
  gas.force_on_gas(gx, gy);
  gas.force_on_walls(wx, wy);
  EXPECT_NEAR(gx, -sx, 1e-12 * std::abs(sy));  // sx may be near 0: scale by the larger total
  EXPECT_NEAR(gy, -sy, 1e-12 * std::abs(sy));
  EXPECT_EQ(wx, 0.0);
  EXPECT_EQ(wy, 0.0);

  // The other convention: the wall cells' outer halves go to the walls; the sum still closes.
  GasParams p = closed_box();
  p.wall_force_to_interior = false;
  GasSolver walls(g, p);
  walls.step(kDt, eps, fx, fy);
  walls.force_on_gas(gx, gy);
  walls.force_on_walls(wx, wy);
  EXPECT_NEAR(gx + wx, -sx, 1e-12 * std::abs(sy));
  EXPECT_NEAR(gy + wy, -sy, 1e-12 * std::abs(sy));
  EXPECT_NE(wy, 0.0);
}

TEST(GasForce, UniformForceIsHeldByThePressure) {
  // Closed bottom, gas at rest, porosity 0.5, F_y = 5000 N/m^3 upwards on the particles (the gas
  // feels -F). At rest -eps dp/dy - F_face / V + rho eps g = 0 face by face. The top exit face
  // (half volume) takes half of the top cell's F; the bottom cells give their lower half to the
  // face above, which takes 1.5 F. So, with e = eps:
  //   p(top cell) = (F/e + rho g) dy / 2,  p_{j-1} - p_j = (F/e + rho g) dy (j >= 2),
  //   p_0 - p_1 = (1.5 F/e + rho g) dy, and the extrapolated wall pressure p_0 + (p_0 - p_1) / 2:
  //   dp = (F/e + rho g) H + 0.75 F dy / e = 9000 + 10.64 + 150 Pa.
  const GasGrid g;
  const double F = 5000.0, e = 0.5, rho_g = 1.205 * 9.81, dy = g.dy(), H = g.height;
  const std::vector<double> eps(g.cells(), e), fx(g.cells(), 0.0), fy(g.cells(), F);
  {
    GasSolver gas(g, closed_box());
    gas.set_porosity(eps);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(gas.step(kDt, eps, fx, fy).converged);
    const double hand = (F / e + rho_g) * H + 0.75 * F * dy / e;
    EXPECT_NEAR(gas.pressure_drop(), hand, 1e-6 * hand);
    EXPECT_LT(max_abs(gas.v()), 1e-9);
    // Bottom row: the face above carries 1.5 F, and the gradient there shows it.
    double gx, gy;
    gas.pressure_gradient(g.index(7, 0), gx, gy);
    EXPECT_NEAR(gy, -(1.5 * F / e + rho_g), 1e-6 * F / e);
    gas.pressure_gradient(g.index(7, 20), gx, gy);
    EXPECT_NEAR(gy, -(F / e + rho_g), 1e-6 * F / e);
  }
  {
    // Walls take the outer halves: the bed's pressure drop is exactly F H / e + rho g H.
    GasParams p = closed_box();
    p.wall_force_to_interior = false;
    GasSolver gas(g, p);
    gas.set_porosity(eps);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(gas.step(kDt, eps, fx, fy).converged);
    const double hand = (F / e + rho_g) * H;
    EXPECT_NEAR(gas.pressure_drop(), hand, 1e-6 * hand);
    double gx, gy;
    gas.pressure_gradient(g.index(7, 0), gx, gy);
    EXPECT_NEAR(gy, -(F / e + rho_g), 1e-6 * F / e);
  }
}

TEST(GasContinuity, ShrinkingPorosityPushesGasOutOfTheTop) {
  // No inflow; the porosity of a block of cells falls (particles arriving) while elsewhere it
  // rises a little: the gas volume that leaves through the exit each step is -sum d(eps)/dt dV.
  const GasGrid g;
  GasSolver gas(g, closed_box());
  std::vector<double> eps(g.cells(), 0.9);
  gas.set_porosity(eps);
  const std::vector<double> zero(g.cells(), 0.0);
  for (int k = 0; k < 50; ++k) {
    std::vector<double> next = eps;
    for (int j = 2; j < 12; ++j)
      for (int i = 3; i < 9; ++i) next[g.index(i, j)] -= 2e-5 * (1.0 + 0.1 * i);  // ~1.5 /s
    for (int i = 0; i < g.nx; ++i) next[g.index(i, 30)] += 1e-6;
    double deps_dt = 0.0;
    for (int c = 0; c < g.cells(); ++c) deps_dt += (next[c] - eps[c]) * g.cell_volume() / kDt;
    const GasStepReport rep = gas.step(kDt, next, zero, zero);
    EXPECT_TRUE(rep.converged) << "step " << k;
    EXPECT_NEAR(gas.outflow(), -deps_dt, 1e-8 * std::abs(deps_dt)) << "step " << k;
    EXPECT_EQ(gas.inflow(), 0.0);
    eps = next;
  }
}

TEST(GasContinuity, GrowingPorositySucksGasInAtTheTop) {
  const GasGrid g;
  GasSolver gas(g, closed_box());
  std::vector<double> eps(g.cells(), 0.5);
  gas.set_porosity(eps);
  const std::vector<double> zero(g.cells(), 0.0);
  for (int k = 0; k < 20; ++k) {
    for (int c = 0; c < g.nx * 10; ++c) eps[c] += 1e-5;
    const GasStepReport rep = gas.step(kDt, eps, zero, zero);
    EXPECT_TRUE(rep.converged);
    const double expected = -g.nx * 10 * 1e-5 * g.cell_volume() / kDt;  // an inflow at the top
    EXPECT_NEAR(gas.outflow(), expected, 1e-8 * std::abs(expected));
  }
}
