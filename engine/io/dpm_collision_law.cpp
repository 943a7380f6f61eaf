#include "io/dpm_collision_law.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "coupling/drag.hpp"
#include "dem/contact_law.hpp"

namespace fluidbed {
namespace {

double sphere_mass(const Settings& s) {
  const double d = s.particles.diameter;
  return s.particles.density * std::numbers::pi * d * d * d / 6.0;
}

constexpr double kReferenceSpeed = 1.0;  // m/s: the bed's collisions are mostly 0.1-2 m/s
constexpr double kSlowSpeed = 0.1, kFastSpeed = 3.0;

// alpha such that dpm_restitution(kn, mass, alpha, speed) == target (bisection; the
// restitution falls as alpha grows).
double alpha_for_restitution(double kn, double mass, double target, double speed) {
  if (target >= 1.0) return 0.0;
  double lo = 0.0, hi = 0.1;
  while (dpm_restitution(kn, mass, hi, speed) > target) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e6) throw InputError("contact.damping: no DPMFoam damping gives this restitution");
  }
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (dpm_restitution(kn, mass, mid, speed) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double dpm_restitution(double kn, double mass, double alpha, double speed) {
  // Scaled: time by 1/omega (omega = sqrt(kn / m)), overlap by speed / omega:
  //   X'' = -X - c X^(1/4) X',  c = alpha (speed / omega)^(1/4),  X(0) = 0, X'(0) = 1.
  const double omega = std::sqrt(kn / mass);
  const double c = alpha * std::pow(speed / omega, 0.25);
  auto acc = [c](double x, double v) { return -x - c * std::pow(std::max(x, 0.0), 0.25) * v; };
  const double h = std::numbers::pi / 20000.0;
  double x = 0.0, v = 1.0;
  for (int k = 0; k < 400000; ++k) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (xn <= 0.0 && k > 0) {
      // Separation inside this step: the velocity where the overlap crosses zero (linear).
      const double f = x / (x - xn);
      return std::fabs(v + f * (vn - v));
    }
    x = xn;
    v = vn;
  }
  return 0.0;  // never separates (overdamped)
}

DpmCollisionLaw dpm_collision_law(const Settings& s) {
  DpmCollisionLaw law;
  const double d = s.particles.diameter, k = s.contact.stiffness, m = sphere_mass(s);
  // kN = (4/3) sqrt(R*) E* with R* = d/4 (pair), d/2 (wall); b = 1.
  law.poissons_ratio = 0.0;
  law.wall_poissons_ratio = 0.0;
  const double nu = law.poissons_ratio, one_nu2 = 1.0 - nu * nu;
  const double estar_pair = 3.0 * k / (4.0 * std::sqrt(d / 4.0));
  const double estar_wall = 3.0 * k / (4.0 * std::sqrt(d / 2.0));
  law.youngs_modulus = 2.0 * one_nu2 * estar_pair;  // E* = E / (2 (1 - nu^2))
  // 1 / E*_wall = (1 - nu^2) / E + (1 - nu_w^2) / E_w
  const double inv_wall = 1.0 / estar_wall - one_nu2 / law.youngs_modulus;
  law.wall_youngs_modulus = (1.0 - law.wall_poissons_ratio * law.wall_poissons_ratio) / inv_wall;
  law.kn_pair = 4.0 / 3.0 * std::sqrt(d / 4.0) * law.youngs_modulus / (2.0 * one_nu2);
  law.kn_wall =
      4.0 / 3.0 * std::sqrt(d / 2.0) /
      (one_nu2 / law.youngs_modulus +
       (1.0 - law.wall_poissons_ratio * law.wall_poissons_ratio) / law.wall_youngs_modulus);
  law.b = 1.0;
  law.mu = s.contact.friction;
  law.reference_speed = kReferenceSpeed;
  law.slow_speed = kSlowSpeed;
  law.fast_speed = kFastSpeed;
  const double m_pair = 0.5 * m;
  law.restitution_pair = restitution_from_damping(k, s.contact.damping, m_pair);
  law.restitution_wall = restitution_from_damping(k, s.contact.damping, m);
  law.alpha_pair = alpha_for_restitution(k, m_pair, law.restitution_pair, kReferenceSpeed);
  law.alpha_wall = alpha_for_restitution(k, m, law.restitution_wall, kReferenceSpeed);
  law.restitution_pair_slow = dpm_restitution(k, m_pair, law.alpha_pair, kSlowSpeed);
  law.restitution_pair_fast = dpm_restitution(k, m_pair, law.alpha_pair, kFastSpeed);
  // Sub-cycling: DPMFoam's (Hertzian) estimate of the contact time over these steps must stay
  // above the scene's dt; our steps per linear contact, pi sqrt(m_pair / k) / dt, do that.
  const double contact_time = contact_duration(k, m_pair);
  law.resolution_steps = std::max(1, static_cast<int>(std::floor(contact_time / s.time.dt)));
  law.peak_overlap_pair = kReferenceSpeed * std::sqrt(m_pair / k);
  const double g_mod = law.youngs_modulus / (2.0 * (1.0 + nu));
  const double gstar = g_mod / (2.0 * (2.0 - nu));
  law.kt_pair = 8.0 * std::sqrt(d / 4.0 * law.peak_overlap_pair) * gstar;
  return law;
}

double wen_yu_over_di_felice(const Settings& s, double eps, double superficial_slip) {
  const double d = s.particles.diameter, rho = s.gas.density, mu = s.gas.viscosity;
  const double slip = superficial_slip / eps;         // interstitial
  const double re = rho * d * superficial_slip / mu;  // Wen-Yu's Re, of the superficial slip
  const double cd = re > 1000.0 ? 0.44 : 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687));
  const double wen_yu =
      std::numbers::pi * d * d / 8.0 * cd * rho * std::pow(eps, -2.65) * slip * slip;
  const double ours = di_felice_drag_magnitude(0.5 * d, rho, mu, eps, slip) / eps;
  return wen_yu / ours;
}

}  // namespace fluidbed
