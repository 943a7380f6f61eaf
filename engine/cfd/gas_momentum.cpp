// The gas's momentum equations (eq 19) on the staggered grid: convecting mass fluxes, the
// Crank-Nicolson operator of each velocity component (first-order upwind convection, viscous
// stress of eq 20), the step's fixed part and the Gauss-Seidel sweeps. Split from
// gas_solver.cpp, which holds the SIMPLE loop, the pressure correction and the boundaries.
#include <algorithm>
#include <cmath>

#include "cfd/gas_solver.hpp"
#include "core/errors.hpp"

namespace fluidbed {

// ---------------------------------------------------------------------------------------------
// Spatial operators. For one momentum component at face f, the convection and viscous terms
// integrated over the face's control volume (N) are
//     L(u)_f = ae u_E + aw u_W + an u_N + as u_S - ap u_P + S,
// with upwind convection through the control-volume faces (mass fluxes interpolated from the
// continuity faces, so a uniform velocity stays uniform), viscous fluxes eps mu du/dn (with the
// 4/3 of the normal stress implicit) and S the cross-derivative part of div(eps tau), which holds
// the other velocity component and is evaluated with the given fields (not implicit).

void GasSolver::mass_fluxes(const double* u, const double* v, const double* eu, const double* ev) {
  const double mx = params_.density * dy_ * dz_, my = params_.density * dx_ * dz_;
  for (std::size_t f = 0; f < m_u_.size(); ++f) m_u_[f] = mx * eu[f] * u[f];
  for (std::size_t f = 0; f < m_v_.size(); ++f) m_v_[f] = my * ev[f] * v[f];
}

// System = false: writes L(u)_f into out (the old level of Crank-Nicolson).
// System = true: the momentum system of the step in cu_: Crank-Nicolson (time term, half the old
// operator, half the new one), F and gravity; the pressure term is added per SIMPLE iteration
// (iteration_source).
template <bool System>
void GasSolver::assemble_u(const double* u, const double* v, const double* eps, const double* ek,
                           double* out) {
  const int nx = nx_, ny = ny_, su = nx + 1;
  const double mu = params_.viscosity;
  const double gx = 4.0 / 3.0 * mu * dy_ * dz_ / dx_, gy = mu * dx_ * dz_ / dy_, sz = mu * dz_;
  const double* mfu = m_u_.data();
  const double* mv = m_v_.data();
  const double rho_v_dt = params_.density * vol_ / dt_, alpha = params_.velocity_relaxation;
  const double ax = dy_ * dz_;
  for (int j = 0; j < ny; ++j) {
    for (int i = 1; i < nx; ++i) {
      const int f = j * su + i;
      const int cE = j * nx + i, cW = cE - 1;  // cells east and west of the face (= v faces below)
      const double Fe = 0.5 * (mfu[f] + mfu[f + 1]), Fw = 0.5 * (mfu[f - 1] + mfu[f]);
      const double Fn = 0.5 * (mv[cW + nx] + mv[cE + nx]), Fs = 0.5 * (mv[cW] + mv[cE]);
      const double De = gx * eps[cE], Dw = gx * eps[cW];
      const double Dn = gy * ek[f + su], Ds = gy * ek[f];
      double ap = De + Dw + std::max(Fe, 0.0) + std::max(-Fw, 0.0);
      const double ae = De + std::max(-Fe, 0.0), aw = Dw + std::max(Fw, 0.0);
      double an = 0.0, as = 0.0;
      if (j + 1 < ny) {
        an = Dn + std::max(-Fn, 0.0);
        ap += Dn + std::max(Fn, 0.0);
      } else {
        ap += Fn;  // exit: ghost = u_P (zero gradient), no viscous flux
      }
      if (j > 0) {
        as = Ds + std::max(Fs, 0.0);
        ap += Ds + std::max(-Fs, 0.0);
      } else {
        ap += 2.0 * Ds + std::max(-Fs, 0.0);  // wall: ghost -u_P; inflow brings no u
      }
      const double S =
          sz * (-2.0 / 3.0 * (eps[cE] * (v[cE + nx] - v[cE]) - eps[cW] * (v[cW + nx] - v[cW])) +
                ek[f + su] * (v[cE + nx] - v[cW + nx]) - ek[f] * (v[cE] - v[cW]));
      if constexpr (!System) {
        double val = ae * u[f + 1] + aw * u[f - 1] - ap * u[f] + S;
        if (j + 1 < ny) val += an * u[f + su];
        if (j > 0) val += as * u[f - su];
        out[f] = val;
      } else {
        const double a = (rho_v_dt * eu_new_[f] + 0.5 * ap) / alpha;
        cu_.ap[f] = a;
        cu_.inv_ap[f] = 1.0 / a;
        cu_.ae[f] = 0.5 * ae;
        cu_.aw[f] = 0.5 * aw;
        cu_.an[f] = 0.5 * an;
        cu_.as[f] = 0.5 * as;
        cu_.b0[f] = rho_v_dt * eu_old_[f] * u_old_[f] + 0.5 * (old_u_[f] + S) - fu_[f];
        cu_.area[f] = eu_new_[f] * ax;  // -eps grad p over the volume = area (p_W - p_E)
      }
    }
  }
}

template <bool System>
void GasSolver::assemble_v(const double* u, const double* v, const double* eps, const double* ek,
                           double* out) {
  const int nx = nx_, ny = ny_, su = nx + 1;
  const double mu = params_.viscosity;
  const double gx = mu * dy_ * dz_ / dx_, gy = 4.0 / 3.0 * mu * dx_ * dz_ / dy_, sz = mu * dz_;
  const double* mfu = m_u_.data();
  const double* mv = m_v_.data();
  const double rho = params_.density, inv_dt = 1.0 / dt_, alpha = params_.velocity_relaxation;
  const double ay = dx_ * dz_, g = params_.gravity;
  for (int j = 1; j <= ny; ++j) {
    const bool top = j == ny;  // the exit face: half control volume below the exit
    const double vcv = top ? 0.5 * vol_ : vol_;
    for (int i = 0; i < nx; ++i) {
      const int f = j * nx + i;
      const int cS = f - nx;            // cell below the face (the face is the cell above's)
      const int uS = (j - 1) * su + i;  // u face west of cell cS
      const int k = j * su + i;         // corner west of the face
      const double Fs = 0.5 * (mv[f - nx] + mv[f]);
      double Fe, Fw, De, Dw;
      if (top) {
        Fe = 0.5 * mfu[uS + 1];
        Fw = 0.5 * mfu[uS];
        De = 0.5 * gx * ek[k + 1];
        Dw = 0.5 * gx * ek[k];
      } else {
        Fe = 0.5 * (mfu[uS + 1] + mfu[uS + 1 + su]);
        Fw = 0.5 * (mfu[uS] + mfu[uS + su]);
        De = gx * ek[k + 1];
        Dw = gx * ek[k];
      }
      const double Ds = gy * eps[cS];
      double ap = Ds + std::max(-Fs, 0.0);
      const double as = Ds + std::max(Fs, 0.0);
      double an = 0.0, ae = 0.0, aw = 0.0;
      if (!top) {
        const double Fn = 0.5 * (mv[f] + mv[f + nx]);
        const double Dn = gy * eps[f];
        an = Dn + std::max(-Fn, 0.0);
        ap += Dn + std::max(Fn, 0.0);
      } else {
        ap += mv[f];  // exit: ghost = v_P (zero gradient), no viscous normal stress
      }
      if (i + 1 < nx) {
        ae = De + std::max(-Fe, 0.0);
        ap += De + std::max(Fe, 0.0);
      } else {
        ap += 2.0 * De;  // wall: ghost -v_P, no flux through it
      }
      if (i > 0) {
        aw = Dw + std::max(Fw, 0.0);
        ap += Dw + std::max(-Fw, 0.0);
      } else {
        ap += 2.0 * Dw;
      }
      double S;
      if (top) {
        S = sz * (2.0 / 3.0) * eps[cS] * (u[uS + 1] - u[uS]);
      } else {
        S = sz *
            (-2.0 / 3.0 * (eps[f] * (u[uS + su + 1] - u[uS + su]) - eps[cS] * (u[uS + 1] - u[uS])) +
             ek[k + 1] * (u[uS + su + 1] - u[uS + 1]) - ek[k] * (u[uS + su] - u[uS]));
      }
      if constexpr (!System) {
        double val = as * v[f - nx] - ap * v[f] + S;
        if (!top) val += an * v[f + nx];
        if (i + 1 < nx) val += ae * v[f + 1];
        if (i > 0) val += aw * v[f - 1];
        out[f] = val;
      } else {
        const double t = rho * vcv * inv_dt;
        // The plate: a force -ev ay K (ev v) on the face's volume, implicit, so that in a steady
        // flow the pressure (whose force is ev ay dp) drops by K times the superficial velocity.
        const double plate =
            j == params_.plate_row ? params_.plate_resistance * ev_new_[f] * ev_new_[f] * ay : 0.0;
        const double a = (t * ev_new_[f] + 0.5 * ap + plate) / alpha;
        cv_.ap[f] = a;
        cv_.inv_ap[f] = 1.0 / a;
        cv_.ae[f] = 0.5 * ae;
        cv_.aw[f] = 0.5 * aw;
        cv_.an[f] = 0.5 * an;
        cv_.as[f] = 0.5 * as;
        cv_.b0[f] = t * ev_old_[f] * v_old_[f] + 0.5 * (old_v_[f] + S) - fv_[f] -
                    rho * ev_new_[f] * vcv * g;
        cv_.area[f] = ev_new_[f] * ay;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// One step.

void GasSolver::prepare_step(double dt, const std::vector<double>& eps,
                             const std::vector<double>& fx, const std::vector<double>& fy) {
  // The new level's convecting velocity (all iterations, or the first one with Picard):
  // extrapolated from the last two steps, second order in time. No history yet: u^n.
  const double ratio = s_.dt_previous > 0.0 ? dt / s_.dt_previous : 0.0;
  for (std::size_t f = 0; f < u_ext_.size(); ++f)
    u_ext_[f] = s_.u[f] + ratio * (s_.u[f] - s_.u_previous[f]);
  for (std::size_t f = 0; f < v_ext_.size(); ++f)
    v_ext_[f] = s_.v[f] + ratio * (s_.v[f] - s_.v_previous[f]);

  dt_ = dt;
  u_old_ = s_.u;
  v_old_ = s_.v;
  eps_old_ = s_.eps;
  s_.eps = eps;
  if (faces_current_) {  // the last step's new level is this step's old level
    std::swap(eu_old_, eu_new_);
    std::swap(ev_old_, ev_new_);
    std::swap(ek_old_, ek_new_);
  } else {
    face_porosities(eps_old_, eu_old_, ev_old_, ek_old_);
  }
  face_porosities(s_.eps, eu_new_, ev_new_, ek_new_);
  faces_current_ = true;
  set_inlet(s_.v, s_.superficial_velocity);
  set_inlet(v_ext_, s_.superficial_velocity);

  // F on the faces: half of a cell's F to each of its two faces; the half that falls on a
  // fixed-velocity face (side walls, bottom) goes to the other face or to the wall.
  const int nx = nx_, ny = ny_, su = nx + 1;
  const bool interior = params_.wall_force_to_interior;
  std::fill(fu_.begin(), fu_.end(), 0.0);
  std::fill(fv_.begin(), fv_.end(), 0.0);
  wall_fx_ = wall_fy_ = 0.0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int c = j * nx + i;
      const double hx = 0.5 * fx[c] * vol_, hy = 0.5 * fy[c] * vol_;
      const int w = j * su + i, e = w + 1;
      if (i > 0)
        fu_[w] += hx;
      else if (interior)
        fu_[e] += hx;
      else
        wall_fx_ += hx;
      if (i + 1 < nx)
        fu_[e] += hx;
      else if (interior)
        fu_[w] += hx;
      else
        wall_fx_ += hx;
      if (j > 0)
        fv_[c] += hy;
      else if (interior)
        fv_[c + nx] += hy;
      else
        wall_fy_ += hy;
      fv_[c + nx] += hy;  // the top face is the solved exit face
    }
  }

  // The old level of Crank-Nicolson: the spatial operator at the start of the step.
  mass_fluxes(u_old_.data(), v_old_.data(), eu_old_.data(), ev_old_.data());
  assemble_u<false>(u_old_.data(), v_old_.data(), eps_old_.data(), ek_old_.data(), old_u_.data());
  assemble_v<false>(u_old_.data(), v_old_.data(), eps_old_.data(), ek_old_.data(), old_v_.data());

  // Reference flow for the mass residual.
  double q_in = 0.0, q_eps = 0.0;
  for (int i = 0; i < nx; ++i) q_in += s_.v[i] * dx_ * dz_;
  for (std::size_t c = 0; c < eps.size(); ++c) q_eps += std::abs(eps[c] - eps_old_[c]);
  q_eps *= vol_ / dt;
  q_ref_ = std::max({q_in, q_eps, 1e-3 * grid_.width * dz_});
}

// The new level's convection and cross-viscous terms: at the velocity extrapolated from the last
// two steps (first iteration, and all of them unless params.picard), else at the latest iterate.
void GasSolver::momentum_system(bool first_iteration) {
  if (!first_iteration && !params_.picard) return;
  const double* u = first_iteration ? u_ext_.data() : s_.u.data();
  const double* v = first_iteration ? v_ext_.data() : s_.v.data();
  mass_fluxes(u, v, eu_new_.data(), ev_new_.data());
  assemble_u<true>(u, v, s_.eps.data(), ek_new_.data(), nullptr);
  assemble_v<true>(u, v, s_.eps.data(), ek_new_.data(), nullptr);
}

// b = b0 + the pressure force at the current pressure + the under-relaxation term.
void GasSolver::iteration_source() {
  const int nx = nx_, ny = ny_, su = nx + 1;
  const double r = 1.0 - params_.velocity_relaxation;
  const double* p = s_.p.data();
  for (int j = 0; j < ny; ++j)
    for (int i = 1; i < nx; ++i) {
      const int f = j * su + i, c = j * nx + i;
      cu_.b[f] = cu_.b0[f] + cu_.area[f] * (p[c - 1] - p[c]) + r * cu_.ap[f] * s_.u[f];
    }
  for (int j = 1; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int f = j * nx + i;
      const double p_above = j < ny ? p[f] : 0.0;  // exit pressure 0
      cv_.b[f] = cv_.b0[f] + cv_.area[f] * (p[f - nx] - p_above) + r * cv_.ap[f] * s_.v[f];
    }
}

// Gauss-Seidel sweeps on the interior faces, alternately forward and backward; wall faces stay
// 0. The neighbour updated just before (west going forward, east going back) is added last, so
// that consecutive faces overlap in the processor.
void GasSolver::sweep_u(int sweeps) {
  const int nx = nx_, ny = ny_, su = nx + 1;
  double* u = s_.u.data();
  const Coefficients& c = cu_;
  auto others = [&](int f, int j) {
    double s = c.b[f];
    if (j + 1 < ny) s += c.an[f] * u[f + su];
    if (j > 0) s += c.as[f] * u[f - su];
    return s;
  };
  for (int k = 0; k < sweeps; ++k) {
    if (k % 2 == 0) {
      for (int j = 0; j < ny; ++j)
        for (int i = 1; i < nx; ++i) {
          const int f = j * su + i;
          const double s = others(f, j) + c.ae[f] * u[f + 1];
          u[f] = (s + c.aw[f] * u[f - 1]) * c.inv_ap[f];
        }
    } else {
      for (int j = ny - 1; j >= 0; --j)
        for (int i = nx - 1; i >= 1; --i) {
          const int f = j * su + i;
          const double s = others(f, j) + c.aw[f] * u[f - 1];
          u[f] = (s + c.ae[f] * u[f + 1]) * c.inv_ap[f];
        }
    }
  }
}

void GasSolver::sweep_v(int sweeps) {
  const int nx = nx_, ny = ny_;
  double* v = s_.v.data();
  const Coefficients& c = cv_;
  auto others = [&](int f, int j) {
    double s = c.b[f] + c.as[f] * v[f - nx];
    if (j < ny) s += c.an[f] * v[f + nx];
    return s;
  };
  for (int k = 0; k < sweeps; ++k) {
    if (k % 2 == 0) {
      for (int j = 1; j <= ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const int f = j * nx + i;
          double s = others(f, j);
          if (i + 1 < nx) s += c.ae[f] * v[f + 1];
          if (i > 0) s += c.aw[f] * v[f - 1];
          v[f] = s * c.inv_ap[f];
        }
    } else {
      for (int j = ny; j >= 1; --j)
        for (int i = nx - 1; i >= 0; --i) {
          const int f = j * nx + i;
          double s = others(f, j);
          if (i > 0) s += c.aw[f] * v[f - 1];
          if (i + 1 < nx) s += c.ae[f] * v[f + 1];
          v[f] = s * c.inv_ap[f];
        }
    }
  }
}

// Continuity (18) over each cell, m^3/s: d(eps)/dt dV plus the net outflow.

}  // namespace fluidbed
