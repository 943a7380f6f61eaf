#include "cfd/gas_solver.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/errors.hpp"
#include "core/hash.hpp"

namespace fluidbed {
namespace {

template <class T>
std::string field_error(const std::string& field, T value, const std::string& rule) {
  std::ostringstream os;
  os << "gas." << field << " = " << value << ": " << rule;
  return os.str();
}

// Sum in four interleaved partial sums (short dependency chains; fixed order).
double sum4(const std::vector<double>& a) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t k = 0;
  for (; k + 3 < a.size(); k += 4) {
    s0 += a[k];
    s1 += a[k + 1];
    s2 += a[k + 2];
    s3 += a[k + 3];
  }
  for (; k < a.size(); ++k) s0 += a[k];
  return (s0 + s1) + (s2 + s3);
}

const GasGrid& checked(const GasGrid& g, const GasParams& p) {
  validate_gas(g, p);
  return g;
}

void check_size(const std::vector<double>& v, std::size_t n, const char* name) {
  if (v.size() != n)
    throw InputError(std::string("gas step: ") + name + " has " + std::to_string(v.size()) +
                     " values, the grid has " + std::to_string(n) + " cells");
}

}  // namespace

void validate_gas(const GasGrid& g, const GasParams& p) {
  if (g.nx < 2 || g.ny < 2)
    throw InputError("gas grid: at least 2 x 2 cells are needed (got " + std::to_string(g.nx) +
                     " x " + std::to_string(g.ny) + ")");
  if (!(g.width > 0.0) || !(g.height > 0.0) || !(g.depth > 0.0) || !std::isfinite(g.width) ||
      !std::isfinite(g.height) || !std::isfinite(g.depth))
    throw InputError("gas grid: width, height and depth must be positive");
  if (!(p.density > 0.0) || !std::isfinite(p.density))
    throw InputError(field_error("density", p.density, "must be > 0 (kg/m^3)"));
  if (!(p.viscosity >= 0.0) || !std::isfinite(p.viscosity))
    throw InputError(field_error("viscosity", p.viscosity, "must be >= 0 (Pa s)"));
  if (!std::isfinite(p.gravity))
    throw InputError(field_error("gravity", p.gravity, "must be finite (m/s^2)"));
  if (!(p.superficial_velocity >= 0.0) || !std::isfinite(p.superficial_velocity))
    throw InputError(
        field_error("superficial_velocity", p.superficial_velocity, "must be >= 0 (m/s)"));
  if (p.inlet == InletKind::Jet && p.jets < 1)
    throw InputError(field_error("jets", p.jets, "must be >= 1"));
  if (p.inlet == InletKind::Jet && !(p.jet_width > 0.0 && p.jet_width * p.jets <= g.width)) {
    std::ostringstream rule;
    rule << "must be > 0 and its jets no wider than the bed (" << g.width << " m)";
    throw InputError(field_error("jet_width", p.jet_width, rule.str()));
  }
  if (!(p.tolerance > 0.0) || !std::isfinite(p.tolerance))
    throw InputError(field_error("tolerance", p.tolerance, "must be > 0"));
  if (p.max_iterations < 1)
    throw InputError(field_error("max_iterations", p.max_iterations, "must be >= 1"));
  if (!(p.velocity_relaxation > 0.0 && p.velocity_relaxation <= 1.0))
    throw InputError(
        field_error("velocity_relaxation", p.velocity_relaxation, "must be in (0, 1]"));
  if (!(p.pressure_relaxation > 0.0 && p.pressure_relaxation <= 1.0))
    throw InputError(
        field_error("pressure_relaxation", p.pressure_relaxation, "must be in (0, 1]"));
  if (p.momentum_sweeps < 1)
    throw InputError(field_error("momentum_sweeps", p.momentum_sweeps, "must be >= 1"));
  if (!(p.pressure_tolerance > 0.0 && p.pressure_tolerance < 1.0))
    throw InputError(field_error("pressure_tolerance", p.pressure_tolerance, "must be in (0, 1)"));
  if (p.pressure_max_iterations < 1)
    throw InputError(
        field_error("pressure_max_iterations", p.pressure_max_iterations, "must be >= 1"));
  if (!(p.preconditioner_refresh >= 0.0) || !std::isfinite(p.preconditioner_refresh))
    throw InputError(
        field_error("preconditioner_refresh", p.preconditioner_refresh, "must be >= 0"));
}

GasSolver::GasSolver(const GasGrid& grid, const GasParams& params)
    : grid_(checked(grid, params)),
      params_(params),
      nx_(grid.nx),
      ny_(grid.ny),
      dx_(grid.dx()),
      dy_(grid.dy()),
      dz_(grid.depth),
      vol_(grid.cell_volume()),
      pressure_(grid.nx, grid.ny, params.pressure_method) {
  const std::size_t nu = static_cast<std::size_t>(nx_ + 1) * ny_;
  const std::size_t nv = static_cast<std::size_t>(nx_) * (ny_ + 1);
  const std::size_t nc = static_cast<std::size_t>(nx_) * ny_;
  const std::size_t nk = static_cast<std::size_t>(nx_ + 1) * (ny_ + 1);

  // Inlet: face velocity per unit superficial velocity. A jet slot edge inside a face gives that
  // face its share of the slot, so the inflow is U W dz whatever the alignment.
  inlet_profile_.assign(nx_, 0.0);
  if (params_.inlet == InletKind::Uniform) {
    std::fill(inlet_profile_.begin(), inlet_profile_.end(), 1.0);
  } else if (params_.inlet == InletKind::Jet) {
    const double open = params_.jets * params_.jet_width;
    for (int k = 0; k < params_.jets; ++k) {
      const double centre = (k + 0.5) * grid_.width / params_.jets;
      const double x0 = centre - 0.5 * params_.jet_width, x1 = centre + 0.5 * params_.jet_width;
      for (int i = 0; i < nx_; ++i) {
        double frac = (std::min(x1, (i + 1) * dx_) - std::max(x0, i * dx_)) / dx_;
        if (frac < 1e-9) continue;
        if (frac > 1.0 - 1e-9) frac = 1.0;
        inlet_profile_[i] += frac * grid_.width / open;
      }
    }
  }

  s_.u.assign(nu, 0.0);
  s_.v.assign(nv, 0.0);
  s_.p.assign(nc, 0.0);
  s_.eps.assign(nc, 1.0);
  s_.u_previous.assign(nu, 0.0);
  s_.v_previous.assign(nv, 0.0);
  s_.superficial_velocity = params_.superficial_velocity;
  // Hydrostatic (the discrete rest state: p = rho g dy / 2 in the top row, p = 0 at the exit).
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      s_.p[j * nx_ + i] = params_.density * params_.gravity * (grid_.height - (j + 0.5) * dy_);

  u_old_.assign(nu, 0.0);
  v_old_.assign(nv, 0.0);
  eps_old_.assign(nc, 1.0);
  eu_new_.assign(nu, 1.0);
  eu_old_.assign(nu, 1.0);
  ev_new_.assign(nv, 1.0);
  ev_old_.assign(nv, 1.0);
  ek_new_.assign(nk, 1.0);
  ek_old_.assign(nk, 1.0);
  fu_.assign(nu, 0.0);
  fv_.assign(nv, 0.0);
  old_u_.assign(nu, 0.0);
  old_v_.assign(nv, 0.0);
  u_ext_.assign(nu, 0.0);
  v_ext_.assign(nv, 0.0);
  m_u_.assign(nu, 0.0);
  m_v_.assign(nv, 0.0);
  for (Coefficients* c : {&cu_, &cv_}) {
    const std::size_t n = c == &cu_ ? nu : nv;
    for (auto* a :
         {&c->ap, &c->inv_ap, &c->ae, &c->aw, &c->an, &c->as, &c->b0, &c->b, &c->area, &c->d})
      a->assign(n, 0.0);
  }
  res_.assign(nc, 0.0);
  pcorr_.assign(nc, 0.0);
  s_.preconditioner_u.assign(nu, 0.0);
  s_.preconditioner_v.assign(nv, 0.0);
}

double GasSolver::jet_velocity() const {
  return params_.inlet == InletKind::Jet ? jet_slot_velocity(s_.superficial_velocity, grid_.width,
                                                             params_.jets, params_.jet_width)
                                         : s_.superficial_velocity;
}

void GasSolver::set_superficial_velocity(double u) {
  if (!(u >= 0.0) || !std::isfinite(u))
    throw InputError(field_error("superficial_velocity", u, "must be >= 0 (m/s)"));
  s_.superficial_velocity = u;
}

void GasSolver::set_porosity(const std::vector<double>& eps) {
  check_size(eps, s_.eps.size(), "porosity");
  for (std::size_t c = 0; c < eps.size(); ++c)
    if (!(eps[c] > 0.0 && eps[c] <= 1.0))
      throw InputError("gas porosity " + std::to_string(eps[c]) + " outside (0, 1] in cell (" +
                       std::to_string(c % nx_) + ", " + std::to_string(c / nx_) + ")");
  s_.eps = eps;
  faces_current_ = false;
}

void GasSolver::set_state(const GasState& s) {
  const std::size_t nu = s_.u.size(), nv = s_.v.size(), nc = s_.p.size();
  if (s.u.size() != nu || s.v.size() != nv || s.p.size() != nc || s.eps.size() != nc ||
      s.u_previous.size() != nu || s.v_previous.size() != nv || s.preconditioner_u.size() != nu ||
      s.preconditioner_v.size() != nv)
    throw InputError("gas state does not match the gas grid (" + std::to_string(nx_) + " x " +
                     std::to_string(ny_) + " cells)");
  s_ = s;
  faces_current_ = false;
  pressure_.restore_preconditioner(s_.preconditioner_u, s_.preconditioner_v);
}

std::uint64_t GasSolver::state_hash() const {
  Fnv1a h;
  h.values(s_.u);
  h.values(s_.v);
  h.values(s_.p);
  h.values(s_.eps);
  h.values(s_.preconditioner_u);
  h.values(s_.preconditioner_v);
  h.values(s_.u_previous);
  h.values(s_.v_previous);
  h.value(s_.dt_previous);
  h.value(s_.superficial_velocity);
  h.value(s_.time);
  h.value(s_.steps);
  return h.digest();
}

void GasSolver::fail(const std::string& what) const {
  std::ostringstream os;
  os.precision(6);
  os << "gas: " << what << " at t = " << s_.time << " s (gas step " << s_.steps + 1 << ")";
  throw SimulationFailure(os.str());
}

// ---------------------------------------------------------------------------------------------
// Geometry of a step: porosity at faces (mean of the two cells; porosity 1 at the inlet, the top
// cell's at the exit) and at cell corners (mean of the four cells, zero-gradient ghosts).

void GasSolver::face_porosities(const std::vector<double>& eps, std::vector<double>& eu,
                                std::vector<double>& ev, std::vector<double>& ek) const {
  const int nx = nx_, ny = ny_;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i)
      eu[j * (nx + 1) + i] =
          0.5 * (eps[j * nx + std::max(i - 1, 0)] + eps[j * nx + std::min(i, nx - 1)]);
  for (int i = 0; i < nx; ++i) {
    ev[i] = 1.0;
    ev[ny * nx + i] = eps[(ny - 1) * nx + i];
  }
  for (int j = 1; j < ny; ++j)
    for (int i = 0; i < nx; ++i) ev[j * nx + i] = 0.5 * (eps[(j - 1) * nx + i] + eps[j * nx + i]);
  for (int j = 0; j <= ny; ++j) {
    const int j0 = std::max(j - 1, 0), j1 = std::min(j, ny - 1);
    for (int i = 0; i <= nx; ++i) {
      const int i0 = std::max(i - 1, 0), i1 = std::min(i, nx - 1);
      ek[j * (nx + 1) + i] =
          0.25 * (eps[j0 * nx + i0] + eps[j0 * nx + i1] + eps[j1 * nx + i0] + eps[j1 * nx + i1]);
    }
  }
}

void GasSolver::set_inlet(std::vector<double>& v, double superficial) const {
  for (int i = 0; i < nx_; ++i) v[i] = inlet_profile_[i] * superficial;
}

double GasSolver::inflow() const {
  double q = 0.0;
  for (int i = 0; i < nx_; ++i) q += s_.v[i];
  return q * dx_ * dz_;
}

double GasSolver::outflow() const {
  double q = 0.0;
  for (int i = 0; i < nx_; ++i) q += s_.eps[(ny_ - 1) * nx_ + i] * s_.v[ny_ * nx_ + i];
  return q * dx_ * dz_;
}

void GasSolver::force_on_gas(double& fx, double& fy) const {
  fx = fy = 0.0;
  for (double f : fu_) fx -= f;
  for (double f : fv_) fy -= f;
}

void GasSolver::force_on_walls(double& fx, double& fy) const {
  fx = -wall_fx_;
  fy = -wall_fy_;
}

double GasSolver::continuity_residual() {
  const int nx = nx_, ny = ny_, su = nx + 1;
  const double ax = dy_ * dz_, ay = dx_ * dz_, rate = vol_ / dt_;
  const double* u = s_.u.data();
  const double* v = s_.v.data();
  double sum = 0.0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int c = j * nx + i, f = j * su + i;
      const double r = (s_.eps[c] - eps_old_[c]) * rate +
                       (eu_new_[f + 1] * u[f + 1] - eu_new_[f] * u[f]) * ax +
                       (ev_new_[c + nx] * v[c + nx] - ev_new_[c] * v[c]) * ay;
      res_[c] = -r;  // right-hand side of the pressure-correction equation
      sum += std::abs(r);
    }
  }
  return sum;
}

// Pressure-correction equation (its face coefficients from the first iteration's momentum
// diagonal, kept for the step), then the velocity and pressure corrections.
void GasSolver::correct(bool first_iteration, GasStepReport& rep) {
  const int nx = nx_, ny = ny_, su = nx + 1;
  if (first_iteration) {
    std::vector<double>& pu = pressure_.coefficients_u();
    std::vector<double>& pv = pressure_.coefficients_v();
    for (int j = 0; j < ny; ++j)
      for (int i = 1; i < nx; ++i) {
        const int f = j * su + i;
        cu_.d[f] = cu_.area[f] * cu_.inv_ap[f];
        pu[f] = cu_.area[f] * cu_.d[f];
      }
    for (int j = 1; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int f = j * nx + i;
        cv_.d[f] = cv_.area[f] * cv_.inv_ap[f];
        pv[f] = cv_.area[f] * cv_.d[f];
      }
    // A NaN from the momentum equations would otherwise first show as a broken matrix.
    if (!std::isfinite(sum4(pu) + sum4(pv))) report_non_finite("in the momentum equations");
    if (pressure_.update_preconditioner(params_.preconditioner_refresh)) {
      rep.preconditioner_rebuilt = true;
      s_.preconditioner_u = pressure_.factored_u();
      s_.preconditioner_v = pressure_.factored_v();
    }
  }
  // Solve to the relative tolerance, or until the mass error left is far below the SIMPLE one.
  const double floor = 1e-3 * params_.tolerance * q_ref_;
  const PressureSolveReport pr =
      pressure_.solve(res_.data(), pcorr_.data(), params_.pressure_tolerance, floor,
                      params_.pressure_max_iterations);
  rep.pressure_iterations_total += pr.iterations;
  rep.pressure_residual = std::max(rep.pressure_residual, pr.relative_residual);

  const double* pc = pcorr_.data();
  double* u = s_.u.data();
  double* v = s_.v.data();
  for (int j = 0; j < ny; ++j)
    for (int i = 1; i < nx; ++i) {
      const int f = j * su + i, c = j * nx + i;
      u[f] += cu_.d[f] * (pc[c - 1] - pc[c]);
    }
  for (int j = 1; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int f = j * nx + i;
      v[f] += cv_.d[f] * (pc[f - nx] - (j < ny ? pc[f] : 0.0));
    }
  const double ap = params_.pressure_relaxation;
  for (std::size_t c = 0; c < s_.p.size(); ++c) s_.p[c] += ap * pc[c];
  // A NaN or an overflow anywhere shows in a sum.
  if (!std::isfinite(sum4(s_.u) + sum4(s_.v) + sum4(s_.p)))
    report_non_finite("after a SIMPLE iteration");
}

void GasSolver::report_non_finite(const char* what) const {
  const int nx = nx_;
  for (std::size_t f = 0; f < s_.u.size(); ++f)
    if (!std::isfinite(s_.u[f]))
      fail(std::string("x-velocity is not finite ") + what + " on the face west of cell (" +
           std::to_string(f % (nx + 1)) + ", " + std::to_string(f / (nx + 1)) + ")");
  for (std::size_t f = 0; f < s_.v.size(); ++f)
    if (!std::isfinite(s_.v[f]))
      fail(std::string("y-velocity is not finite ") + what + " on the face below cell (" +
           std::to_string(f % nx) + ", " + std::to_string(f / nx) + ")");
  for (std::size_t c = 0; c < s_.p.size(); ++c)
    if (!std::isfinite(s_.p[c]))
      fail(std::string("pressure is not finite ") + what + " in cell (" + std::to_string(c % nx) +
           ", " + std::to_string(c / nx) + ")");
  fail(std::string("a value overflowed ") + what);
}

double GasSolver::max_cfl(double dt, int& face, bool& is_u) const {
  double umax = 0.0, vmax = 0.0;
  int fu = 0, fv = 0;
  for (std::size_t f = 0; f < s_.u.size(); ++f)
    if (std::abs(s_.u[f]) > umax) {
      umax = std::abs(s_.u[f]);
      fu = static_cast<int>(f);
    }
  for (std::size_t f = 0; f < s_.v.size(); ++f)
    if (std::abs(s_.v[f]) > vmax) {
      vmax = std::abs(s_.v[f]);
      fv = static_cast<int>(f);
    }
  is_u = umax > vmax;
  face = is_u ? fu : fv;
  return std::max(umax, vmax) * dt / std::min(dx_, dy_);
}

GasStepReport GasSolver::step(double dt, const std::vector<double>& eps,
                              const std::vector<double>& fx, const std::vector<double>& fy) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw InputError("gas step: dt = " + std::to_string(dt) + " s must be > 0");
  const std::size_t nc = s_.p.size();
  check_size(eps, nc, "porosity");
  check_size(fx, nc, "fx");
  check_size(fy, nc, "fy");
  for (std::size_t c = 0; c < nc; ++c) {
    if (!(eps[c] > 0.0 && eps[c] <= 1.0))
      fail("porosity " + std::to_string(eps[c]) + " outside (0, 1] in cell (" +
           std::to_string(c % nx_) + ", " + std::to_string(c / nx_) + ")");
    if (!std::isfinite(fx[c]) || !std::isfinite(fy[c]))
      fail("interaction force F is not finite in cell (" + std::to_string(c % nx_) + ", " +
           std::to_string(c / nx_) + ")");
  }

  // A step that starts near the CFL limit keeps its starting state: if the flow outruns it within
  // the step, the step is taken again as sub-steps (see kSplitFromCfl).
  const double start_cfl =
      std::max(max_speed_per_cell(), jet_velocity() / std::min(dx_, dy_)) * dt;
  std::optional<GasState> start;
  if (start_cfl > kSplitFromCfl && start_cfl <= 1.0) start = s_;
  GasStepReport rep = solve(dt, eps, fx, fy);
  if (rep.max_cfl <= 1.0 || !start) {
    check(rep, dt);
    commit(dt);
    return rep;
  }
  const int n = std::min(kMaxSubsteps, static_cast<int>(std::ceil(rep.max_cfl / kSubstepCfl)));
  set_state(*start);
  const std::vector<double>& old_eps = start->eps;
  std::vector<double> level(nc);
  GasStepReport total;
  total.converged = true;
  for (int k = 1; k <= n; ++k) {
    // The porosity moves linearly from its old level to eps over the sub-steps; the particles'
    // force is the same in each.
    const double w = static_cast<double>(k) / n;
    for (std::size_t c = 0; c < nc; ++c)
      level[c] = k == n ? eps[c] : old_eps[c] + w * (eps[c] - old_eps[c]);
    const GasStepReport r = solve(dt / n, level, fx, fy);
    check(r, dt / n);
    commit(dt / n);
    total.simple_iterations += r.simple_iterations;
    total.mass_residual = std::max(total.mass_residual, r.mass_residual);
    total.pressure_iterations_total += r.pressure_iterations_total;
    total.pressure_residual = std::max(total.pressure_residual, r.pressure_residual);
    total.converged = total.converged && r.converged;
    total.max_cfl = std::max(total.max_cfl, r.max_cfl);
    total.preconditioner_rebuilt = total.preconditioner_rebuilt || r.preconditioner_rebuilt;
  }
  total.substeps = n;
  return total;
}

GasStepReport GasSolver::solve(double dt, const std::vector<double>& eps,
                               const std::vector<double>& fx, const std::vector<double>& fy) {
  prepare_step(dt, eps, fx, fy);
  GasStepReport rep;
  const double tol = params_.tolerance;
  for (int it = 0; it < params_.max_iterations; ++it) {
    const bool first = it == 0;
    momentum_system(first);
    iteration_source();
    sweep_u(params_.momentum_sweeps);
    sweep_v(params_.momentum_sweeps);
    rep.mass_residual = continuity_residual() / q_ref_;
    correct(first, rep);
    rep.simple_iterations = it + 1;
    if (rep.mass_residual < tol) {
      rep.converged = true;
      break;
    }
  }
  rep.max_cfl = max_cfl(dt, cfl_face_, cfl_face_is_u_);
  return rep;
}

void GasSolver::check(const GasStepReport& rep, double dt) const {
  if (rep.max_cfl > 1.0) {
    const int face = cfl_face_;
    const bool is_u = cfl_face_is_u_;
    const int i = is_u ? face % (nx_ + 1) : face % nx_;
    const int j = is_u ? face / (nx_ + 1) : face / nx_;
    std::ostringstream os;
    os.precision(4);
    os << "CFL number " << rep.max_cfl << " > 1 (velocity " << (is_u ? s_.u[face] : s_.v[face])
       << " m/s on the " << (is_u ? "west" : "bottom") << " face of cell (" << std::min(i, nx_ - 1)
       << ", " << std::min(j, ny_ - 1) << "), dt = " << dt << " s): the gas "
       << (!is_u && j == 0 ? "enters" : "moves") << " more than a cell in one gas step";
    fail(os.str());
  }
  const double tol = params_.tolerance;
  if (!rep.converged && rep.mass_residual > 1000.0 * tol) {
    std::size_t worst = 0;
    for (std::size_t c = 0; c < res_.size(); ++c)
      if (std::abs(res_[c]) > std::abs(res_[worst])) worst = c;
    std::ostringstream os;
    os.precision(4);
    os << "SIMPLE did not converge in " << rep.simple_iterations << " iterations (mass residual "
       << rep.mass_residual << ", tolerance " << tol << "; largest residual in cell ("
       << worst % nx_ << ", " << worst / nx_ << "))";
    fail(os.str());
  }
}

void GasSolver::commit(double dt) {
  s_.u_previous = u_old_;
  s_.v_previous = v_old_;
  s_.dt_previous = dt;
  s_.time += dt;
  ++s_.steps;
}

// ---------------------------------------------------------------------------------------------
// Read access.

double GasSolver::bottom_pressure(int i) const {
  return 1.5 * s_.p[i] - 0.5 * s_.p[nx_ + i];
}

double GasSolver::pressure_drop() const {
  if (nx_ % 2 == 1) return bottom_pressure(nx_ / 2);
  return 0.5 * (bottom_pressure(nx_ / 2 - 1) + bottom_pressure(nx_ / 2));
}

void GasSolver::pressure_gradient(int c, double& gx, double& gy) const {
  const int nx = nx_, i = c % nx, j = c / nx;
  const double* p = s_.p.data();
  const double pe = i + 1 < nx ? 0.5 * (p[c] + p[c + 1]) : 1.5 * p[c] - 0.5 * p[c - 1];
  const double pw = i > 0 ? 0.5 * (p[c] + p[c - 1]) : 1.5 * p[c] - 0.5 * p[c + 1];
  const double pn = j + 1 < ny_ ? 0.5 * (p[c] + p[c + nx]) : 0.0;
  const double ps = j > 0 ? 0.5 * (p[c] + p[c - nx]) : 1.5 * p[c] - 0.5 * p[c + nx];
  gx = (pe - pw) / dx_;
  gy = (pn - ps) / dy_;
}

}  // namespace fluidbed
