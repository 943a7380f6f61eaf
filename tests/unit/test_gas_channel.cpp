// The gas solver against closed-form flows: plane Poiseuille flow between the side walls (uniform
// inflow at the bottom, the paper's gas and grid spacing), and the jet inlet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cfd/gas_solver.hpp"
#include "core/errors.hpp"

using namespace fluidbed;

namespace {

struct SteadyRun {
  int steps = 0;
  int worst_iterations = 0;
  double worst_residual = 0.0;
  bool all_converged = true;
  double last_change = 0.0;  // max |v^(n+1) - v^n| / U at the last step
};

// Steps with a fixed porosity and no force until the flow stops changing.
SteadyRun run_to_steady(GasSolver& gas, double dt, int max_steps, double change_tol) {
  const GasGrid& g = gas.grid();
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  const double U = gas.superficial_velocity();
  SteadyRun r;
  std::vector<double> before;
  for (r.steps = 1; r.steps <= max_steps; ++r.steps) {
    before = gas.v();
    const GasStepReport rep = gas.step(dt, eps, zero, zero);
    r.all_converged &= rep.converged && rep.mass_residual < gas.params().tolerance;
    r.worst_iterations = std::max(r.worst_iterations, rep.simple_iterations);
    r.worst_residual = std::max(r.worst_residual, rep.mass_residual);
    double change = 0.0;
    for (std::size_t f = 0; f < before.size(); ++f)
      change = std::max(change, std::abs(gas.v()[f] - before[f]));
    r.last_change = change / U;
    if (r.last_change < change_tol) break;
  }
  return r;
}

GasParams channel_params(double U) {
  GasParams p;
  p.inlet = InletKind::Uniform;
  p.superficial_velocity = U;
  return p;
}

}  // namespace

TEST(GasChannel, PoiseuilleProfileInTheUpperPart) {
  // The paper's grid (15 x 45 cells, dx = 10 mm) and air, at U = 2 mm/s: Re = U W / nu = 20, so
  // the entrance length is about 1.2 W = 0.18 m (Durst et al. 2005) and the upper half of the
  // 0.9 m channel is fully developed. dt = 2 s keeps the CFL number at 0.6; the viscous time
  // W^2 / nu is 1500 s, so the flow is steady after a few hundred steps.
  const GasGrid g;
  const double U = 0.002;
  GasSolver gas(g, channel_params(U));
  const SteadyRun run = run_to_steady(gas, 2.0, 3000, 1e-10);
  ASSERT_LT(run.last_change, 1e-10) << "not steady after " << run.steps << " steps";
  EXPECT_TRUE(run.all_converged);
  EXPECT_LT(run.worst_residual, 1e-6);

  // Analytic: v(x) = 6 U x (W - x) / W^2, 1.5 U on the centreline. The ghost-cell wall gives the
  // discrete profile a small slip; on N cells the centreline value is 1.5 U (N^2 + 1) / (N^2 + 2)
  // (the exact solution of the discrete equations), 0.44 % below 1.5 U for N = 15.
  const double W = g.width, N = g.nx;
  const double discrete_centre = 1.5 * (N * N + 1.0) / (N * N + 2.0);
  for (int j = g.ny / 2; j <= g.ny; ++j) {  // faces from y = 0.44 m to the exit
    const double centre = gas.v()[j * g.nx + g.nx / 2] / U;
    EXPECT_NEAR(centre, 1.5, 0.02 * 1.5) << "row " << j;
    EXPECT_NEAR(centre, discrete_centre, 2e-4) << "row " << j;
    for (int i = 0; i < g.nx; ++i) {
      const double x = (i + 0.5) * g.dx();
      const double analytic = 6.0 * x * (W - x) / (W * W);
      EXPECT_NEAR(gas.v()[j * g.nx + i] / U, analytic, 0.02 * 1.5) << "row " << j << " col " << i;
    }
  }
  // Mass: the inflow is U W dz; what comes in goes out.
  EXPECT_NEAR(gas.inflow(), U * W * g.depth, 1e-12 * U * W * g.depth);
  EXPECT_NEAR(gas.outflow(), gas.inflow(), 1e-8 * gas.inflow());
  // The horizontal flow of the entrance region has died out (it decays by about 3x per row:
  // 2e-3 U at y = 0.25 m, 5e-5 U at y = 0.45 m).
  for (int j = g.ny / 2; j < g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i)
      EXPECT_LT(std::abs(gas.u()[j * (g.nx + 1) + i]), 1e-4 * U) << "row " << j;
}

TEST(GasChannel, PicardAndExtrapolatedConvectionReachTheSameSteadyState) {
  // The two ways of handling the nonlinear convection differ only in time: at steady state the
  // convecting velocity is the same, so are the fields.
  const GasGrid g;
  const double U = 0.002;
  GasParams pp = channel_params(U);
  pp.picard = true;
  GasSolver extrapolated(g, channel_params(U)), picard(g, pp);
  const SteadyRun a = run_to_steady(extrapolated, 2.0, 3000, 1e-11);
  const SteadyRun b = run_to_steady(picard, 2.0, 3000, 1e-11);
  ASSERT_LT(a.last_change, 1e-11);
  ASSERT_LT(b.last_change, 1e-11);
  EXPECT_TRUE(a.all_converged);
  EXPECT_TRUE(b.all_converged);
  double dv = 0.0;
  for (std::size_t f = 0; f < extrapolated.v().size(); ++f)
    dv = std::max(dv, std::abs(extrapolated.v()[f] - picard.v()[f]));
  EXPECT_LT(dv, 1e-8 * U);
  EXPECT_NEAR(extrapolated.pressure_drop(), picard.pressure_drop(), 1e-9);
}

TEST(GasJet, SlotFacesCarryTheJetAndTheInflowIsUWidthDepth) {
  // The paper: U = 2.8 m/s over the 0.15 m bottom through a 10 mm slot gives 42 m/s.
  const GasGrid g;
  GasParams p;  // defaults: jet, 2.8 m/s, 10 mm
  GasSolver gas(g, p);
  EXPECT_NEAR(gas.jet_velocity(), 42.0, 1e-12);
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  for (int k = 0; k < 20; ++k) {
    const GasStepReport rep = gas.step(1.5e-5, eps, zero, zero);
    EXPECT_TRUE(rep.converged);
    EXPECT_NEAR(rep.max_cfl, 42.0 * 1.5e-5 / 0.01, 0.1);  // the jet face itself: 0.063
  }
  for (int i = 0; i < g.nx; ++i)
    EXPECT_DOUBLE_EQ(gas.v()[i], i == 7 ? 42.0 : 0.0) << "bottom face " << i;
  const double q = 2.8 * g.width * g.depth;
  EXPECT_NEAR(gas.inflow(), q, 1e-12 * q);
  EXPECT_NEAR(gas.outflow(), q, 1e-8 * q);  // constant porosity: what comes in goes out
}

TEST(GasJet, SlotBetweenTwoFacesSharesTheFlow) {
  // nx even: the centred 10 mm slot covers half of each of the two middle faces.
  GasGrid g;
  g.nx = 16;
  g.width = 0.16;
  GasParams p;
  p.superficial_velocity = 1.0;
  GasSolver gas(g, p);
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  gas.step(1e-5, eps, zero, zero);
  for (int i = 0; i < g.nx; ++i)
    EXPECT_NEAR(gas.v()[i], (i == 7 || i == 8) ? 0.5 * 16.0 : 0.0, 1e-12) << "face " << i;
  EXPECT_NEAR(gas.inflow(), 1.0 * g.width * g.depth, 1e-15);
  EXPECT_NEAR(gas.outflow(), gas.inflow(), 1e-8 * gas.inflow());
}

TEST(GasJet, SuperficialVelocityChangesAtTheNextStep) {
  const GasGrid g;
  GasSolver gas(g, GasParams{});
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  gas.step(1.5e-5, eps, zero, zero);
  gas.set_superficial_velocity(1.0);
  EXPECT_DOUBLE_EQ(gas.v()[7], 42.0);  // not yet
  gas.step(1.5e-5, eps, zero, zero);
  EXPECT_DOUBLE_EQ(gas.v()[7], 15.0);
  EXPECT_THROW(gas.set_superficial_velocity(-1.0), InputError);
}
