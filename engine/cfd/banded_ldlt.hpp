#pragma once
// LDL^T factorization of a symmetric positive definite five-point matrix on an nx x ny grid of
// cells (c = j * nx + i), stored as a band of half-width nx. The gas grid is small (15 x 45 by
// default), so the band (nx * ny * nx values) fits in cache and a factorization costs about
// nx^2 ny / 2 multiply-adds; a solve costs 2 nx^2 ny. No allocation after construction.
#include <vector>

namespace fluidbed {

class BandedLdlt {
 public:
  BandedLdlt(int nx, int ny);

  // Factorizes the matrix with diagonal diag[c], east coupling east[c] = A(c, c + 1) (0 in the
  // last column) and north coupling north[c] = A(c, c + nx) (0 in the top row). Returns false
  // when a pivot is not positive (the matrix is not positive definite).
  bool factorize(const double* diag, const double* east, const double* north);

  // x = A^-1 b; b and x may be the same array.
  void solve(const double* b, double* x) const;

  int size() const { return n_; }

 private:
  int nx_, n_;
  // Row k holds L(k, k - nx .. k - 1) at l_[k * nx + m], m = column - (k - nx); u_ holds L^T
  // by rows (L(k + 1 .. k + nx, k)), so that both triangular solves read contiguous rows.
  std::vector<double> l_, u_;
  std::vector<double> inv_d_;  // 1 / D(k)
  std::vector<double> w_;      // scratch: L(k, m) D(m) for the current row
};

}  // namespace fluidbed
