#include "dem/integrators.hpp"

namespace fluidbed {

void predict(Integrator integrator, double h, Particles& P, std::size_t b, std::size_t e) {
  double* x = P.x.data();
  double* y = P.y.data();
  double* vx = P.vx.data();
  double* vy = P.vy.data();
  double* w = P.w.data();
  const double* ax = P.ax.data();
  const double* ay = P.ay.data();
  const double* aw = P.aw.data();
  switch (integrator) {
    case Integrator::Newmark: {
      const double hh4 = 0.25 * h * h;
      for (std::size_t i = b; i < e; ++i) {
        x[i] += h * vx[i] + hh4 * ax[i];
        y[i] += h * vy[i] + hh4 * ay[i];
        vx[i] += 0.5 * h * ax[i];
        vy[i] += 0.5 * h * ay[i];
        w[i] += 0.5 * h * aw[i];
      }
      break;
    }
    case Integrator::VelocityVerlet:  // kick half, drift, forces with the half-step velocity
      for (std::size_t i = b; i < e; ++i) {
        vx[i] += 0.5 * h * ax[i];
        vy[i] += 0.5 * h * ay[i];
        w[i] += 0.5 * h * aw[i];
        x[i] += h * vx[i];
        y[i] += h * vy[i];
      }
      break;
    case Integrator::SymplecticEuler:  // forces first
      break;
  }
}

void correct(Integrator integrator, double h, Particles& P, std::size_t b, std::size_t e) {
  double* x = P.x.data();
  double* y = P.y.data();
  double* vx = P.vx.data();
  double* vy = P.vy.data();
  double* w = P.w.data();
  double* ax = P.ax.data();
  double* ay = P.ay.data();
  double* aw = P.aw.data();
  const double* fx = P.fx.data();
  const double* fy = P.fy.data();
  const double* tq = P.torque.data();
  const double* im = P.inv_mass.data();
  const double* ii = P.inv_inertia.data();
  switch (integrator) {
    case Integrator::Newmark: {
      const double hh4 = 0.25 * h * h;
      for (std::size_t i = b; i < e; ++i) {
        const double axi = fx[i] * im[i], ayi = fy[i] * im[i], awi = tq[i] * ii[i];
        vx[i] += 0.5 * h * axi;
        vy[i] += 0.5 * h * ayi;
        w[i] += 0.5 * h * awi;
        x[i] += hh4 * axi;
        y[i] += hh4 * ayi;
        ax[i] = axi;
        ay[i] = ayi;
        aw[i] = awi;
      }
      break;
    }
    case Integrator::VelocityVerlet:
      for (std::size_t i = b; i < e; ++i) {
        ax[i] = fx[i] * im[i];
        ay[i] = fy[i] * im[i];
        aw[i] = tq[i] * ii[i];
        vx[i] += 0.5 * h * ax[i];
        vy[i] += 0.5 * h * ay[i];
        w[i] += 0.5 * h * aw[i];
      }
      break;
    case Integrator::SymplecticEuler:
      for (std::size_t i = b; i < e; ++i) {
        ax[i] = fx[i] * im[i];
        ay[i] = fy[i] * im[i];
        aw[i] = tq[i] * ii[i];
        vx[i] += h * ax[i];
        vy[i] += h * ay[i];
        w[i] += h * aw[i];
        x[i] += h * vx[i];
        y[i] += h * vy[i];
      }
      break;
  }
}

}  // namespace fluidbed
