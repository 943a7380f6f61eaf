#include "cfd/pressure_solver.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace fluidbed {
namespace {

// In four interleaved partial sums: short dependency chains, a fixed order.
double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t k = 0;
  for (; k + 3 < a.size(); k += 4) {
    s0 += a[k] * b[k];
    s1 += a[k + 1] * b[k + 1];
    s2 += a[k + 2] * b[k + 2];
    s3 += a[k + 3] * b[k + 3];
  }
  for (; k < a.size(); ++k) s0 += a[k] * b[k];
  return (s0 + s1) + (s2 + s3);
}

// Whether every coefficient is within a fraction `threshold` of the factored one (a coefficient
// that appears or vanishes is not).
bool close(const std::vector<double>& now, const std::vector<double>& then, double threshold) {
  bool ok = true;
  for (std::size_t k = 0; k < now.size(); ++k)
    ok &= std::abs(now[k] - then[k]) <= threshold * then[k];
  return ok;
}

}  // namespace

PressureSolver::PressureSolver(int nx, int ny, PressureMethod method)
    : nx_(nx),
      ny_(ny),
      n_(nx * ny),
      multigrid_(method == PressureMethod::multigrid ||
                 (method == PressureMethod::automatic && std::min(nx, ny) > kMultigridBand)),
      cu_(static_cast<std::size_t>(nx + 1) * ny, 0.0),
      cv_(static_cast<std::size_t>(nx) * (ny + 1), 0.0),
      fu_(cu_.size(), 0.0),
      fv_(cv_.size(), 0.0),
      diag_(n_, 0.0),
      east_(n_, 0.0),
      north_(n_, 0.0),
      transposed_(!multigrid_ && nx > ny),
      ldlt_(multigrid_ ? 1 : (nx > ny ? ny : nx), multigrid_ ? 1 : (nx > ny ? nx : ny)),
      r_(n_, 0.0),
      z_(n_, 0.0),
      p_(n_, 0.0),
      q_(n_, 0.0) {}

void PressureSolver::assemble(const std::vector<double>& cu, const std::vector<double>& cv) {
  const int nx = nx_;
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int c = j * nx + i;
      const double w = cu[j * (nx + 1) + i], e = cu[j * (nx + 1) + i + 1];
      const double s = cv[j * nx + i], n = cv[(j + 1) * nx + i];
      diag_[c] = w + e + s + n;
      east_[c] = i + 1 < nx ? -e : 0.0;
      north_[c] = j + 1 < ny_ ? -n : 0.0;
    }
  }
}

void PressureSolver::refactorize() {
  fu_ = cu_;
  fv_ = cv_;
  assemble(fu_, fv_);
  ++factorizations_;
  factored_ = true;
  bool ok = false;
  if (multigrid_) {
    ok = mg_.build(nx_, ny_, diag_.data(), east_.data(), north_.data());
  } else if (transposed_) {
    // Cell (i, j) is c' = i ny + j: its "east" neighbour in the band is (i, j + 1) (the north
    // coupling), its "north" one is (i + 1, j) (the east coupling).
    t_diag_.resize(n_);
    t_east_.resize(n_);
    t_north_.resize(n_);
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const int c = j * nx_ + i, t = i * ny_ + j;
        t_diag_[t] = diag_[c];
        t_east_[t] = north_[c];
        t_north_[t] = east_[c];
      }
    ok = ldlt_.factorize(t_diag_.data(), t_east_.data(), t_north_.data());
  } else {
    ok = ldlt_.factorize(diag_.data(), east_.data(), north_.data());
  }
  if (!ok)
    throw SimulationFailure(
        "gas pressure-correction matrix is not positive definite (NaN or negative face "
        "coefficient)");
}

bool PressureSolver::update_preconditioner(double threshold) {
  if (factored_ && close(cu_, fu_, threshold) && close(cv_, fv_, threshold)) return false;
  refactorize();
  return true;
}

void PressureSolver::restore_preconditioner(const std::vector<double>& cu,
                                            const std::vector<double>& cv) {
  // All zero: the state was saved before any factorization; build one at the next solve.
  const auto zero = [](const std::vector<double>& c) {
    return std::all_of(c.begin(), c.end(), [](double x) { return x == 0.0; });
  };
  if (zero(cu) && zero(cv)) {
    std::fill(fu_.begin(), fu_.end(), 0.0);
    std::fill(fv_.begin(), fv_.end(), 0.0);
    factored_ = false;
    return;
  }
  const std::vector<double> keep_u = cu_, keep_v = cv_;
  cu_ = cu;
  cv_ = cv;
  refactorize();
  cu_ = keep_u;
  cv_ = keep_v;
}

void PressureSolver::multiply(const double* x, double* y) const {
  const int nx = nx_;
  for (int j = 0; j < ny_; ++j) {
    const double* cu = &cu_[static_cast<std::size_t>(j) * (nx + 1)];
    const double* cs = &cv_[static_cast<std::size_t>(j) * nx];
    const double* cn = cs + nx;
    for (int i = 0; i < nx; ++i) {
      const int c = j * nx + i;
      double s = (cu[i] + cu[i + 1] + cs[i] + cn[i]) * x[c];
      if (i > 0) s -= cu[i] * x[c - 1];
      if (i + 1 < nx) s -= cu[i + 1] * x[c + 1];
      if (j > 0) s -= cs[i] * x[c - nx];
      if (j + 1 < ny_) s -= cn[i] * x[c + nx];
      y[c] = s;
    }
  }
}

void PressureSolver::precondition(const double* r, double* z) {
  if (multigrid_) {
    mg_.apply(r, z);
    return;
  }
  if (!transposed_) {
    ldlt_.solve(r, z);
    return;
  }
  t_r_.resize(n_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) t_r_[i * ny_ + j] = r[j * nx_ + i];
  ldlt_.solve(t_r_.data(), t_r_.data());
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i) z[j * nx_ + i] = t_r_[i * ny_ + j];
}

PressureSolveReport PressureSolver::solve(const double* b, double* x, double rel_tol,
                                          double abs_tol, int max_iterations) {
  PressureSolveReport rep;
  for (int k = 0; k < n_; ++k) {
    x[k] = 0.0;
    r_[k] = b[k];
  }
  const double bnorm = std::sqrt(dot(r_, r_));
  if (bnorm == 0.0) {
    rep.converged = true;
    return rep;
  }
  const double target = std::max(rel_tol * bnorm, abs_tol);
  precondition(r_.data(), z_.data());
  p_ = z_;
  double rz = dot(r_, z_);
  double rnorm = bnorm;
  while (rep.iterations < max_iterations) {
    multiply(p_.data(), q_.data());
    const double pq = dot(p_, q_);
    if (!(pq > 0.0)) break;  // breakdown (NaN or exact solution already reached)
    const double alpha = rz / pq;
    for (int k = 0; k < n_; ++k) {
      x[k] += alpha * p_[k];
      r_[k] -= alpha * q_[k];
    }
    ++rep.iterations;
    rnorm = std::sqrt(dot(r_, r_));
    if (rnorm <= target) break;
    precondition(r_.data(), z_.data());
    const double rz_new = dot(r_, z_);
    const double beta = rz_new / rz;
    rz = rz_new;
    for (int k = 0; k < n_; ++k) p_[k] = z_[k] + beta * p_[k];
  }
  rep.relative_residual = rnorm / bnorm;
  rep.converged = rnorm <= target;
  return rep;
}

}  // namespace fluidbed
