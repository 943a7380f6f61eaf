#include "coupling/drag.hpp"

#include <numbers>

#include "core/simd.hpp"

namespace fluidbed {

namespace {
double sphere_volume(double R) {
  return 4.0 / 3.0 * std::numbers::pi * R * R * R;
}
}  // namespace

FLUIDBED_SIMD_CLONES void di_felice_beta_many(std::size_t n, const double* R, const double* eps,
                                              const double* ln_eps, const double* slip,
                                              double rho_f, double mu_f, double* beta) {
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i)
    beta[i] = di_felice_beta_ln(R[i], rho_f, mu_f, eps[i], ln_eps[i], slip[i]);
}

double slip_for_drag_force(double R, double rho_f, double mu_f, double eps, double force) {
  if (!(force > 0.0)) return 0.0;
  // Start from the zero-slip (Stokes-like) estimate; double until the drag exceeds the force.
  double lo = 0.0;
  double hi = force / di_felice_beta(R, rho_f, mu_f, eps, 0.0);
  for (int k = 0; k < 2000 && di_felice_drag_magnitude(R, rho_f, mu_f, eps, hi) < force; ++k) {
    lo = hi;
    hi *= 2.0;
  }
  // Bisection until the bracket cannot shrink (at most about 1100 halvings of a double range;
  // in practice 52 or so).
  for (int k = 0; k < 2000; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if (di_felice_drag_magnitude(R, rho_f, mu_f, eps, mid) < force) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

double terminal_slip_velocity(double R, double rho_p, double rho_f, double mu_f, double eps,
                              double g, bool buoyancy) {
  const double rho = buoyancy ? rho_p - rho_f : rho_p;
  return slip_for_drag_force(R, rho_f, mu_f, eps, rho * sphere_volume(R) * g);
}

double ergun_pressure_gradient(double U, double eps, double d, double rho_f, double mu_f) {
  const double e3 = eps * eps * eps;
  return 150.0 * mu_f * (1.0 - eps) * (1.0 - eps) * U / (e3 * d * d) +
         1.75 * rho_f * (1.0 - eps) * U * U / (e3 * d);
}

double di_felice_umf(double R, double rho_p, double rho_f, double mu_f, double eps, double g) {
  const double f = eps * sphere_volume(R) * (rho_p - rho_f) * g;
  return eps * slip_for_drag_force(R, rho_f, mu_f, eps, f);
}

double di_felice_umf_printed(double R, double rho_p, double rho_f, double mu_f, double eps,
                             double g) {
  const double f = rho_p * sphere_volume(R) * g;
  return eps * slip_for_drag_force(R, rho_f, mu_f, eps, f);
}

}  // namespace fluidbed
