#pragma once
// A multigrid preconditioner for the pressure correction's five-point matrix (cfd/
// pressure_solver.hpp), of linear cost in the number of cells: one symmetric V-cycle per
// application. Coarse cells are 2 x 2 blocks of finer ones (the last row or column of an odd
// grid alone); the coarse matrix is the Galerkin product of the piecewise-constant prolongation
// (a coarse face's coupling is the sum of the fine couplings across it), so every level keeps the
// five-point form and stays symmetric positive definite. Smoothing: one zebra line Gauss-Seidel
// sweep (the even rows of cells solved exactly along x, then the odd ones) on the way down and
// the same in the other order (odd rows, then even) on the way up, so that the cycle is a
// symmetric positive definite operator and conjugate gradients may use it. The coarsest level (a
// few hundred cells) is solved exactly by a banded LDL^T. A piecewise-constant coarse correction
// is too short by about half on a Poisson-like matrix; it is scaled by kCorrection (measured:
// BM_GasStepGrid's and bench_pressure.cpp's iteration counts). Serial, in a fixed order: the same
// bits on every run.
#include <memory>
#include <vector>

#include "cfd/banded_ldlt.hpp"

namespace fluidbed {

class MultigridPreconditioner {
 public:
  // The scale of the coarse-grid correction (1: Galerkin's own).
  static constexpr double kCorrection = 1.8;
  // Coarsening stops at this many cells or fewer, or when a side is below 4 cells.
  static constexpr int kCoarsest = 400;

  // The hierarchy for the matrix with diagonal diag[c], east coupling east[c] = A(c, c + 1)
  // (0 in the last column) and north coupling north[c] = A(c, c + nx) (0 in the top row),
  // c = j nx + i. Returns false when a level is not positive definite.
  bool build(int nx, int ny, const double* diag, const double* east, const double* north);
  // z = M^-1 r: one V-cycle from z = 0. r and z must not overlap.
  void apply(const double* r, double* z);
  int levels() const { return static_cast<int>(levels_.size()); }

 private:
  struct Level {
    int nx = 0, ny = 0;
    std::vector<double> diag, east, north;
    // Each row's Thomas factors (cfd/multigrid.cpp; empty on the coarsest level, never swept).
    std::vector<double> row_mul, row_inv;
    std::vector<double> x, b;  // this level's unknowns and right-hand side
    std::vector<double> r;     // one row's residual (scratch)
  };
  std::vector<Level> levels_;
  std::unique_ptr<BandedLdlt> coarse_;
  void cycle(std::size_t l);
};

}  // namespace fluidbed
