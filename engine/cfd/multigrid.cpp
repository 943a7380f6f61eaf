#include "cfd/multigrid.hpp"

#include <algorithm>

namespace fluidbed {
namespace {

// The coarse matrix of `f` (Galerkin, 2 x 2 aggregates) into `c`.
void coarsen(const auto& f, auto& c) {
  c.nx = (f.nx + 1) / 2;
  c.ny = (f.ny + 1) / 2;
  const auto n = static_cast<std::size_t>(c.nx) * c.ny;
  c.diag.assign(n, 0.0);
  c.east.assign(n, 0.0);
  c.north.assign(n, 0.0);
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * f.nx + i;
      const std::size_t C = static_cast<std::size_t>(j / 2) * c.nx + i / 2;
      c.diag[C] += f.diag[k];
      if (i + 1 < f.nx) {
        if ((i + 1) / 2 == i / 2)
          c.diag[C] += 2.0 * f.east[k];  // a coupling inside the aggregate
        else
          c.east[C] += f.east[k];
      }
      if (j + 1 < f.ny) {
        if ((j + 1) / 2 == j / 2)
          c.diag[C] += 2.0 * f.north[k];
        else
          c.north[C] += f.north[k];
      }
    }
}

// One Gauss-Seidel sweep of A x = b, forward (cells in increasing order) or backward. A cell's
// update waits for the neighbour just updated, so that term is taken last and the diagonal is
// multiplied by its inverse: the chain from one cell to the next is a multiply, a subtraction
// and a multiply, not a division (measured: BM_PressureSolveMultigrid).
void sweep(auto& L, bool forward) {
  const int nx = L.nx, ny = L.ny;
  const double* inv = L.inv_diag.data();
  const double* e = L.east.data();
  const double* no = L.north.data();
  double* x = L.x.data();
  const double* b = L.b.data();
  const auto others = [&](int j, int c) {  // b minus the rows below and above
    double s = b[c];
    if (j > 0) s -= no[c - nx] * x[c - nx];
    if (j + 1 < ny) s -= no[c] * x[c + nx];
    return s;
  };
  if (forward) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int c = j * nx + i;
        double s = others(j, c);
        if (i + 1 < nx) s -= e[c] * x[c + 1];
        if (i > 0) s -= e[c - 1] * x[c - 1];
        x[c] = s * inv[c];
      }
  } else {
    for (int j = ny - 1; j >= 0; --j)
      for (int i = nx - 1; i >= 0; --i) {
        const int c = j * nx + i;
        double s = others(j, c);
        if (i > 0) s -= e[c - 1] * x[c - 1];
        if (i + 1 < nx) s -= e[c] * x[c + 1];
        x[c] = s * inv[c];
      }
  }
}

// r = b - A x.
void residual(auto& L) {
  const int nx = L.nx, ny = L.ny;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int c = j * nx + i;
      double s = L.b[c] - L.diag[c] * L.x[c];
      if (i > 0) s -= L.east[c - 1] * L.x[c - 1];
      if (i + 1 < nx) s -= L.east[c] * L.x[c + 1];
      if (j > 0) s -= L.north[c - nx] * L.x[c - nx];
      if (j + 1 < ny) s -= L.north[c] * L.x[c + nx];
      L.r[c] = s;
    }
}

}  // namespace

bool MultigridPreconditioner::build(int nx, int ny, const double* diag, const double* east,
                                    const double* north) {
  levels_.resize(1);
  Level& top = levels_[0];
  top.nx = nx;
  top.ny = ny;
  const auto n = static_cast<std::size_t>(nx) * ny;
  top.diag.assign(diag, diag + n);
  top.east.assign(east, east + n);
  top.north.assign(north, north + n);
  while (levels_.back().nx * levels_.back().ny > kCoarsest && levels_.back().nx >= 4 &&
         levels_.back().ny >= 4) {
    Level next;
    coarsen(levels_.back(), next);
    levels_.push_back(std::move(next));
  }
  for (Level& L : levels_) {
    const auto m = static_cast<std::size_t>(L.nx) * L.ny;
    L.x.assign(m, 0.0);
    L.b.assign(m, 0.0);
    L.r.assign(m, 0.0);
    if (&L == &levels_.back()) break;  // solved exactly, never swept
    L.inv_diag.resize(m);
    for (std::size_t k = 0; k < m; ++k) L.inv_diag[k] = 1.0 / L.diag[k];
  }
  const Level& c = levels_.back();
  coarse_ = std::make_unique<BandedLdlt>(c.nx, c.ny);
  return coarse_->factorize(c.diag.data(), c.east.data(), c.north.data());
}

void MultigridPreconditioner::cycle(std::size_t l) {
  Level& L = levels_[l];
  if (l + 1 == levels_.size()) {
    coarse_->solve(L.b.data(), L.x.data());
    return;
  }
  std::fill(L.x.begin(), L.x.end(), 0.0);
  sweep(L, true);
  residual(L);
  Level& C = levels_[l + 1];
  std::fill(C.b.begin(), C.b.end(), 0.0);
  for (int j = 0; j < L.ny; ++j)
    for (int i = 0; i < L.nx; ++i)
      C.b[static_cast<std::size_t>(j / 2) * C.nx + i / 2] +=
          L.r[static_cast<std::size_t>(j) * L.nx + i];
  cycle(l + 1);
  for (int j = 0; j < L.ny; ++j)
    for (int i = 0; i < L.nx; ++i)
      L.x[static_cast<std::size_t>(j) * L.nx + i] +=
          kCorrection * C.x[static_cast<std::size_t>(j / 2) * C.nx + i / 2];
  sweep(L, false);
}

void MultigridPreconditioner::apply(const double* r, double* z) {
  Level& top = levels_[0];
  std::copy(r, r + top.b.size(), top.b.begin());
  cycle(0);
  std::copy(top.x.begin(), top.x.end(), z);
}

}  // namespace fluidbed
