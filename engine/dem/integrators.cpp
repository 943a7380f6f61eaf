#include "dem/integrators.hpp"

namespace fluidbed {

void predict(Integrator integrator, double h, Particles& P, std::size_t b, std::size_t e) {
  const auto a = P.arrays();
  switch (integrator) {
    case Integrator::Newmark: {
      const double hh4 = 0.25 * h * h;
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

void correct(Integrator integrator, double h, Particles& P, std::size_t b, std::size_t e) {
  const auto a = P.arrays();
  switch (integrator) {
    case Integrator::Newmark: {
      const double hh4 = 0.25 * h * h;
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
