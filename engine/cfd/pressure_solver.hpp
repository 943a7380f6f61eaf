#pragma once
// The pressure-correction equation of SIMPLE on the gas grid, solved by preconditioned conjugate
// gradients. The matrix is the five-point sum over a cell's faces of c_f (p'_P - p'_nb) (SPD: the
// exit pressure is fixed, so the top faces tie p' to 0). Its preconditioner is an exact banded
// LDL^T factorization of the matrix as it was at some earlier step: the coefficients follow the
// porosity, which moves by less than 1e-3 per particle step, so a factorization stays a
// near-exact inverse for many steps and PCG converges in one or two iterations. It is rebuilt
// when any coefficient has moved by more than a set fraction since it was made. The coefficients
// the factorization was made from are part of the gas state, so a restart is bit-exact.
#include <vector>

#include "cfd/banded_ldlt.hpp"
#include "cfd/multigrid.hpp"

namespace fluidbed {

struct PressureSolveReport {
  int iterations = 0;              // PCG iterations (0 when the right-hand side is already 0)
  double relative_residual = 0.0;  // ||b - A x||_2 / ||b||_2 at the end (0 when b = 0)
  bool converged = false;
};

// The preconditioner: the banded factorization (exact for the matrix it was made from; its cost
// per cell grows with the band's width, the grid's short side) or a multigrid V-cycle
// (cfd/multigrid.hpp; more PCG iterations, a cost per cell that grows slowly). `automatic`
// takes multigrid where the short side passes kMultigridBand cells. Measured with
// BM_GasStepGrid (the gas step of a bed on the paper's 10 x 20 mm cells and finer ones of the
// same shape, each preconditioner forced, ns per cell and SIMPLE iteration, medians of 3 in
// bench/results-amd-epyc-2core.csv, banded against multigrid): 40 x 120, 62 against 59; 50 x
// 150, 67 against 64; 65 x 195, 117 against 63; 80 x 240, 151 against 58; and on wide grids of 45
// rows, whose band stays narrow: 150 x 45, 61 against 63; 1500 x 45 (the 240,000-sphere bed), 87
// against 82 (kept banded: within this machine's noise). Every shipped scene's grid is banded
// (the paper's 15 x 45, van Wachem's finest 36 x 200). The others are for tests and benchmarks.
enum class PressureMethod { automatic, banded, multigrid };

class PressureSolver {
 public:
  static constexpr int kMultigridBand = 56;
  PressureSolver(int nx, int ny, PressureMethod method = PressureMethod::automatic);
  bool multigrid() const { return multigrid_; }

  // Face coefficients c_f in m^3/(s Pa): the change of the volume flow through face f per unit
  // pressure-correction difference across it. cu: vertical faces, index j * (nx + 1) + i (the
  // side walls i = 0 and i = nx carry 0); cv: horizontal faces, index j * nx + i (row 0, the
  // bottom, carries 0: its velocity is fixed; row ny, the exit, couples to p' = 0 outside).
  std::vector<double>& coefficients_u() { return cu_; }
  std::vector<double>& coefficients_v() { return cv_; }

  // Rebuilds the factorization when a coefficient has moved by more than `threshold` (relative)
  // since the last one; returns true when it did. Throws SimulationFailure when the matrix is not
  // positive definite (a NaN or a negative coefficient).
  bool update_preconditioner(double threshold);

  // Solves A x = b from x = 0; stops when ||r||_2 <= max(rel_tol ||b||_2, abs_tol).
  PressureSolveReport solve(const double* b, double* x, double rel_tol, double abs_tol,
                            int max_iterations);

  // y = A x (for checks).
  void multiply(const double* x, double* y) const;

  // The coefficients the current factorization was built from (saved with the gas state).
  const std::vector<double>& factored_u() const { return fu_; }
  const std::vector<double>& factored_v() const { return fv_; }
  // Rebuilds the factorization from saved coefficients (a loaded state).
  void restore_preconditioner(const std::vector<double>& cu, const std::vector<double>& cv);

  int factorizations() const { return factorizations_; }

 private:
  void assemble(const std::vector<double>& cu, const std::vector<double>& cv);
  void refactorize();

  int nx_, ny_, n_;
  bool multigrid_;
  std::vector<double> cu_, cv_;              // current coefficients
  std::vector<double> fu_, fv_;              // coefficients of the factorization
  std::vector<double> diag_, east_, north_;  // the five-point matrix (current or factored)
  // The factorization's band runs along the shorter side of the grid: a bed wider than tall
  // (many jets side by side) is factored with its cells numbered column by column, so the cost
  // per cell stays 2 min(nx, ny) and grows with the bed like the particle count.
  bool transposed_ = false;
  BandedLdlt ldlt_;  // 1 x 1 when the multigrid preconditions
  MultigridPreconditioner mg_;
  std::vector<double> t_diag_, t_east_, t_north_, t_r_;  // the transposed copies (when used)
  std::vector<double> r_, z_, p_, q_;  // PCG work vectors

  void precondition(const double* r, double* z);
  int factorizations_ = 0;
  bool factored_ = false;
};

}  // namespace fluidbed
