#include "dem/integrators.hpp"

#include <vector>

#include "core/simd.hpp"

namespace fluidbed {

namespace {

// The depth arrays of a thick slab (Particles::has_depth) go through the same formulas as x and
// w, component by component, in a loop of their own so that the monolayer's loops stay as they
// were: z from vz and az, the spin about x and y from their rates.

// vz, wx and wy advanced by k times their rates (a kick of the thick slab's own components).
__attribute__((always_inline)) inline void kick_depth(Particles& P, std::size_t b, std::size_t e,
                                                      double k) {
  double *vz = P.vz.data(), *wx = P.wx.data(), *wy = P.wy.data();
  const double *az = P.az.data(), *awx = P.awx.data(), *awy = P.awy.data();
#pragma omp simd
  for (std::size_t i = b; i < e; ++i) {
    vz[i] += k * az[i];
    wx[i] += k * awx[i];
    wy[i] += k * awy[i];
  }
}

// z advanced by k times the array v (vz or az).
__attribute__((always_inline)) inline void drift_depth(Particles& P, std::size_t b, std::size_t e,
                                                       double k, const std::vector<double>& v) {
  double* z = P.z.data();
  const double* dz = v.data();
#pragma omp simd
  for (std::size_t i = b; i < e; ++i) z[i] += k * dz[i];
}

__attribute__((always_inline)) inline void predict_depth(Integrator integrator, double h,
                                                         Particles& P, std::size_t b,
                                                         std::size_t e) {
  switch (integrator) {
    case Integrator::Newmark: {
      double *z = P.z.data(), *vz = P.vz.data();
      const double* az = P.az.data();
      const double hh4 = 0.25 * h * h;
#pragma omp simd
      for (std::size_t i = b; i < e; ++i) z[i] += h * vz[i] + hh4 * az[i];
      kick_depth(P, b, e, 0.5 * h);
      break;
    }
    case Integrator::VelocityVerlet:
      kick_depth(P, b, e, 0.5 * h);
      drift_depth(P, b, e, h, P.vz);
      break;
    case Integrator::SymplecticEuler:
      break;
  }
}

// The new accelerations, then the integrator's kick and drift, each a loop with no branch.
__attribute__((always_inline)) inline void correct_depth(Integrator integrator, double h,
                                                         Particles& P, std::size_t b,
                                                         std::size_t e) {
  double *az = P.az.data(), *awx = P.awx.data(), *awy = P.awy.data();
  const double *fz = P.fz.data(), *tx = P.torque_x.data(), *ty = P.torque_y.data();
  const double *im = P.inv_mass.data(), *ii = P.inv_inertia.data();
#pragma omp simd
  for (std::size_t i = b; i < e; ++i) {
    az[i] = fz[i] * im[i];
    awx[i] = tx[i] * ii[i];
    awy[i] = ty[i] * ii[i];
  }
  switch (integrator) {
    case Integrator::Newmark:
      kick_depth(P, b, e, 0.5 * h);
      drift_depth(P, b, e, 0.25 * h * h, P.az);
      break;
    case Integrator::VelocityVerlet:
      kick_depth(P, b, e, 0.5 * h);
      break;
    case Integrator::SymplecticEuler:
      kick_depth(P, b, e, h);
      drift_depth(P, b, e, h, P.vz);
      break;
  }
}

}  // namespace

FLUIDBED_SIMD_CLONES void predict(Integrator integrator, double h, Particles& P, std::size_t b,
                                  std::size_t e) {
  if (P.has_depth()) predict_depth(integrator, h, P, b, e);
  const auto a = P.arrays();
  switch (integrator) {
    case Integrator::Newmark: {
      const double hh4 = 0.25 * h * h;
#pragma omp simd
      for (std::size_t i = b; i < e; ++i) {
        a.x[i] += h * a.vx[i] + hh4 * a.ax[i];
        a.y[i] += h * a.vy[i] + hh4 * a.ay[i];
        a.vx[i] += 0.5 * h * a.ax[i];
        a.vy[i] += 0.5 * h * a.ay[i];
        a.w[i] += 0.5 * h * a.aw[i];
      }
      break;
    }
    case Integrator::VelocityVerlet:  // kick half, drift, forces with the half-step velocity
#pragma omp simd
      for (std::size_t i = b; i < e; ++i) {
        a.vx[i] += 0.5 * h * a.ax[i];
        a.vy[i] += 0.5 * h * a.ay[i];
        a.w[i] += 0.5 * h * a.aw[i];
        a.x[i] += h * a.vx[i];
        a.y[i] += h * a.vy[i];
      }
      break;
    case Integrator::SymplecticEuler:  // forces first
      break;
  }
}

FLUIDBED_SIMD_CLONES void correct(Integrator integrator, double h, Particles& P, std::size_t b,
                                  std::size_t e) {
  if (P.has_depth()) correct_depth(integrator, h, P, b, e);
  const auto a = P.arrays();
  switch (integrator) {
    case Integrator::Newmark: {
      const double hh4 = 0.25 * h * h;
#pragma omp simd
      for (std::size_t i = b; i < e; ++i) {
        const double axi = a.fx[i] * a.inv_mass[i], ayi = a.fy[i] * a.inv_mass[i];
        const double awi = a.torque[i] * a.inv_inertia[i];
        a.vx[i] += 0.5 * h * axi;
        a.vy[i] += 0.5 * h * ayi;
        a.w[i] += 0.5 * h * awi;
        a.x[i] += hh4 * axi;
        a.y[i] += hh4 * ayi;
        a.ax[i] = axi;
        a.ay[i] = ayi;
        a.aw[i] = awi;
      }
      break;
    }
    case Integrator::VelocityVerlet:
#pragma omp simd
      for (std::size_t i = b; i < e; ++i) {
        a.ax[i] = a.fx[i] * a.inv_mass[i];
        a.ay[i] = a.fy[i] * a.inv_mass[i];
        a.aw[i] = a.torque[i] * a.inv_inertia[i];
        a.vx[i] += 0.5 * h * a.ax[i];
        a.vy[i] += 0.5 * h * a.ay[i];
        a.w[i] += 0.5 * h * a.aw[i];
      }
      break;
    case Integrator::SymplecticEuler:
#pragma omp simd
      for (std::size_t i = b; i < e; ++i) {
        a.ax[i] = a.fx[i] * a.inv_mass[i];
        a.ay[i] = a.fy[i] * a.inv_mass[i];
        a.aw[i] = a.torque[i] * a.inv_inertia[i];
        a.vx[i] += h * a.ax[i];
        a.vy[i] += h * a.ay[i];
        a.w[i] += h * a.aw[i];
        a.x[i] += h * a.vx[i];
        a.y[i] += h * a.vy[i];
      }
      break;
  }
}

}  // namespace fluidbed
