#pragma once
// Gas drag on a particle: Di Felice (1994), Xu & Yu 1997 eqs 8-12, with eps inside Re_p (the
// Reynolds number of the superficial slip, model.md section 2):
//   Re_p = 2 rho_f R eps |u - v| / mu_f                                   (12)
//   C_d0 = (0.63 + 4.8 / sqrt(Re_p))^2                                    (11)
//   chi  = 3.7 - 0.65 exp(-(1.5 - log10 Re_p)^2 / 2)                      (10)
//   f_f  = 0.5 C_d0 rho_f pi R^2 eps^2 |u - v| (u - v) eps^(-chi)         (8, 9)
// u is the interstitial gas velocity (of the cell holding the centre), v the particle's.
// Plus the closed-form checks that go with it: terminal slip, minimum fluidization, Ergun.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "core/fast_math.hpp"

namespace fluidbed {

// Drag on one particle and its drag coefficient, for an implicit update later.
struct DragForce {
  double fx = 0.0;    // N, on the particle, along u - v
  double fy = 0.0;    // N
  double beta = 0.0;  // kg/s, |f_f| / |u - v| (finite at zero slip: the Stokes-like limit)
};

// beta = |f_f| / |u - v| for slip speed `slip` = |u - v| >= 0 (m/s); R in m, rho_f in kg/m^3,
// mu_f in Pa s, 0 < eps <= 1. With C_d0 = (0.63 sqrt(Re) + 4.8)^2 / Re and Re = k |u - v|,
// k = 2 rho_f R eps / mu_f, the slip cancels:
//   beta = (pi mu_f R / 4) (0.63 sqrt(Re) + 4.8)^2 eps^(1 - chi),
// so beta is smooth down to zero slip, where it tends to 5.76 pi mu_f R eps^-2.7 (chi -> 3.7;
// Stokes would be 6 pi mu_f R at eps = 1). Cost: one sqrt, one log10, one exp, one pow.
// The same with ln(eps) given, so a cell's logarithm is taken once for all its particles:
// eps^(1 - chi) = exp((1 - chi) ln eps). This is the form the coupler evaluates for every
// particle at every step: its log and exps are core/fast_math.hpp's (within 2 ulp of libm's,
// inlined and branch-free), which made it about four times cheaper than with libm's calls.
inline double di_felice_beta_ln(double R, double rho_f, double mu_f, double eps, double ln_eps,
                                double slip) {
  constexpr double kTinyRe = 1e-30;
  constexpr double kInvLn10 = 0.43429448190325182765;
  const double re = 2.0 * rho_f * R * eps * slip / mu_f;  // eq 12
  // re + 1e-30 rather than max(re, 1e-30) (no branch, so the loop vectorises): the same bits
  // for any re above 1e-14, and re >= 0.
  const double l = 1.5 - kInvLn10 * fast_log(re + kTinyRe);
  const double chi = 3.7 - 0.65 * fast_exp(-0.5 * l * l);  // eq 10
  const double c = 0.63 * std::sqrt(re) + 4.8;              // sqrt(C_d0 Re), eq 11
  return 0.25 * std::numbers::pi * mu_f * R * c * c * fast_exp((1.0 - chi) * ln_eps);  // eqs 8, 9
}

// di_felice_beta_ln for particles [0, n) from arrays: the coupler's hot loop. Pure arithmetic
// over arrays, built for SSE2, AVX2 and AVX-512 and chosen for the CPU at run time (the same
// operations in the same order: the same bits on each; no fused multiply-add, -ffp-contract=off).
void di_felice_beta_many(std::size_t n, const double* R, const double* eps, const double* ln_eps,
                         const double* slip, double rho_f, double mu_f, double* beta);

inline double di_felice_beta(double R, double rho_f, double mu_f, double eps, double slip) {
  // Below Re = 1e-30, exp(-(1.5 - log10 Re)^2 / 2) < 1e-200: chi is 3.7 to the last bit, and
  // the floor keeps log10 away from 0 (no -inf, no floating-point exception at zero slip).
  constexpr double kTinyRe = 1e-30;
  const double re = 2.0 * rho_f * R * eps * slip / mu_f;  // eq 12
  const double l = 1.5 - std::log10(std::max(re, kTinyRe));
  const double chi = 3.7 - 0.65 * std::exp(-0.5 * l * l);  // eq 10
  const double c = 0.63 * std::sqrt(re) + 4.8;             // sqrt(C_d0 Re), eq 11
  return 0.25 * std::numbers::pi * mu_f * R * c * c * std::pow(eps, 1.0 - chi);  // eqs 8, 9
}

// The drag force on a particle of radius R (m) in gas of density rho_f (kg/m^3), viscosity mu_f
// (Pa s), porosity eps, interstitial velocity (ux, uy), particle velocity (vx, vy) (m/s).
// Zero slip gives zero force and the finite limit of beta. Cost: beta's plus a sqrt for |u - v|
// (about 37 ns on the development machine).
inline DragForce di_felice_drag(double R, double rho_f, double mu_f, double eps, double ux,
                                double uy, double vx, double vy) {
  const double sx = ux - vx;
  const double sy = uy - vy;
  const double slip = std::sqrt(sx * sx + sy * sy);
  DragForce f;
  f.beta = di_felice_beta(R, rho_f, mu_f, eps, slip);
  f.fx = f.beta * sx;
  f.fy = f.beta * sy;
  return f;
}

// |f_f| at slip speed `slip` (N).
inline double di_felice_drag_magnitude(double R, double rho_f, double mu_f, double eps,
                                       double slip) {
  return di_felice_beta(R, rho_f, mu_f, eps, slip) * slip;
}

// The slip speed (m/s) at which the Di Felice drag magnitude equals `force` (N): bracket by
// doubling, then bisection to the last bit. The drag grows monotonically with slip for
// eps > 0.003 (d ln f / d ln Re >= 1 - 0.171 |ln eps|, 0.171 = max |d chi / d ln Re|), so the
// root is unique. Returns 0 for force <= 0.
double slip_for_drag_force(double R, double rho_f, double mu_f, double eps, double force);

// The slip speed at which the drag balances a particle's weight (rho_p V_p g) or, with
// buoyancy, its weight less the displaced gas ((rho_p - rho_f) V_p g). g in m/s^2.
double terminal_slip_velocity(double R, double rho_p, double rho_f, double mu_f, double eps,
                              double g, bool buoyancy);

// Ergun's pressure gradient (Pa/m) through a fixed bed of porosity eps of spheres of diameter d
// (m) at superficial velocity U (m/s):
//   150 mu_f (1 - eps)^2 U / (eps^3 d^2) + 1.75 rho_f (1 - eps) U^2 / (eps^3 d).
double ergun_pressure_gradient(double U, double eps, double d, double rho_f, double mu_f);

// Minimum fluidization velocity (superficial, m/s) of a bed of porosity eps with Di Felice drag
// and model A (particles feel drag and -V_p grad p; model.md 2.1). Steady uniform bed at rest,
// G = -dp/dy, n = (1 - eps) / V_p particles per volume, f the drag on one particle:
//   particle:  f + V_p G = rho_p V_p g
//   gas:       eps G = n f + eps rho_f g
// Eliminating G: f (1 + (1 - eps) / eps) = V_p (rho_p - rho_f) g, that is
//   f_f(slip = U / eps, eps) = eps V_p (rho_p - rho_f) g,
// and then G - rho_f g = (1 - eps)(rho_p - rho_f) g: the bed carries exactly its buoyant weight.
double di_felice_umf(double R, double rho_p, double rho_f, double mu_f, double eps, double g);

// The same with the paper's printed form: the particles feel the drag alone and the paper
// neglects buoyancy, so at incipient fluidization f_f(slip = U / eps, eps) = rho_p V_p g (the
// gas then carries eps G = n f: G = W / (eps L A), twice the bed's weight per area).
double di_felice_umf_printed(double R, double rho_p, double rho_f, double mu_f, double eps,
                             double g);

}  // namespace fluidbed
