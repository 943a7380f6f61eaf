// Order of accuracy in time of the gas solver: Crank-Nicolson for the momentum equations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/gas_solver.hpp"

using namespace fluidbed;

namespace {

// Closed box, porosity 0.7, a force F_y(x, y, t) = 30 sin(2 pi t / 0.1 s) cos(pi x / W)
// sin(pi y / H) N/m^3 that stirs the gas up to about 1 m/s; the vertical velocity at t = 0.05 s.
std::vector<double> stirred_box(double dt, bool picard) {
  const GasGrid g;
  GasParams p;
  p.inlet = InletKind::None;
  p.picard = picard;
  p.tolerance = 1e-10;  // so that the iteration error is far below the time error
  p.max_iterations = 200;
  GasSolver gas(g, p);
  const std::vector<double> eps(g.cells(), 0.7), fx(g.cells(), 0.0);
  std::vector<double> fy(g.cells());
  gas.set_porosity(eps);
  const double pi = std::numbers::pi;
  const int steps = static_cast<int>(std::lround(0.05 / dt));
  for (int k = 0; k < steps; ++k) {
    const double t = (k + 0.5) * dt;  // F at the middle of the step
    for (int c = 0; c < g.cells(); ++c) {
      const double x = (c % g.nx + 0.5) * g.dx(), y = (c / g.nx + 0.5) * g.dy();
      fy[c] = 30.0 * std::sin(2.0 * pi * t / 0.1) * std::cos(pi * x / g.width) *
              std::sin(pi * y / g.height);
    }
    EXPECT_TRUE(gas.step(dt, eps, fx, fy).converged);
  }
  return gas.v();
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

}  // namespace

TEST(GasTime, CrankNicolsonIsSecondOrder) {
  // Halving dt divides the error (against dt / 16) by 4: measured 4.01 and 4.05.
  for (bool picard : {false, true}) {
    const std::vector<double> ref = stirred_box(1e-3 / 16, picard);
    const double e1 = max_difference(stirred_box(1e-3, picard), ref);
    const double e2 = max_difference(stirred_box(5e-4, picard), ref);
    const double e4 = max_difference(stirred_box(2.5e-4, picard), ref);
    EXPECT_GT(e1 / e2, 3.6) << "picard " << picard << ": errors " << e1 << " " << e2;
    EXPECT_GT(e2 / e4, 3.6) << "picard " << picard << ": errors " << e2 << " " << e4;
    EXPECT_LT(e1, 1e-3);  // m/s, on velocities of about 1 m/s
  }
}
