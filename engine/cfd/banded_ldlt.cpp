#include "cfd/banded_ldlt.hpp"

#include <algorithm>

namespace fluidbed {
namespace {

// sum_m a[m] b[m] over m < n, in four interleaved partial sums (a fixed order, so the result is
// the same on every run; the short dependency chains make the triangular solves about twice as
// fast as one running sum).
inline double dot(const double* a, const double* b, int n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int m = 0;
  for (; m + 3 < n; m += 4) {
    s0 += a[m] * b[m];
    s1 += a[m + 1] * b[m + 1];
    s2 += a[m + 2] * b[m + 2];
    s3 += a[m + 3] * b[m + 3];
  }
  for (; m < n; ++m) s0 += a[m] * b[m];
  return (s0 + s1) + (s2 + s3);
}

}  // namespace

BandedLdlt::BandedLdlt(int nx, int ny)
    : nx_(nx),
      n_(nx * ny),
      l_(static_cast<std::size_t>(n_) * nx, 0.0),
      u_(static_cast<std::size_t>(n_) * nx, 0.0),
      inv_d_(n_, 0.0),
      w_(nx, 0.0) {}

bool BandedLdlt::factorize(const double* diag, const double* east, const double* north) {
  const int w = nx_;
  for (int k = 0; k < n_; ++k) {
    double* lk = &l_[static_cast<std::size_t>(k) * w];  // lk[col - (k - w)]
    const int j0 = std::max(0, k - w);
    for (int m = 0; m < j0 - (k - w); ++m) lk[m] = 0.0;  // columns before 0 (first rows)
    // Row k of L from the rows above: L(k, j) D(j) = A(k, j) - sum_m L(k, m) D(m) L(j, m).
    for (int j = j0; j < k; ++j) {
      double s = 0.0;
      if (j == k - 1) s = east[j];
      if (j == k - w) s += north[j];
      const double* lj = &l_[static_cast<std::size_t>(j) * w];  // lj[col - (j - w)]
      for (int m = j0; m < j; ++m) s -= w_[m - (k - w)] * lj[m - (j - w)];
      w_[j - (k - w)] = s;  // L(k, j) D(j)
      lk[j - (k - w)] = s * inv_d_[j];
    }
    double dk = diag[k];
    for (int m = j0; m < k; ++m) dk -= w_[m - (k - w)] * lk[m - (k - w)];
    if (!(dk > 0.0)) return false;
    inv_d_[k] = 1.0 / dk;
  }
  // L^T by rows for the backward solve: u_[k * w + (m - k - 1)] = L(m, k), m = k + 1 .. k + w.
  for (int k = 0; k < n_; ++k)
    for (int m = k + 1; m <= std::min(n_ - 1, k + w); ++m)
      u_[static_cast<std::size_t>(k) * w + (m - k - 1)] =
          l_[static_cast<std::size_t>(m) * w + (k - (m - w))];
  return true;
}

// Each row's sum leaves out its nearest neighbour (the unknown just computed) and subtracts it
// last, so the rows overlap in the processor except for one multiply-add each.
void BandedLdlt::solve(const double* b, double* x) const {
  const int w = nx_, n = n_;
  x[0] = b[0];
  for (int k = 1; k < n; ++k) {  // L y = b
    const int j0 = std::max(0, k - w);
    const double* lk = &l_[static_cast<std::size_t>(k) * w];
    const double far = b[k] - dot(lk + (j0 - (k - w)), x + j0, k - 1 - j0);
    x[k] = far - lk[w - 1] * x[k - 1];
  }
  for (int k = 0; k < n; ++k) x[k] *= inv_d_[k];  // D z = y
  for (int k = n - 2; k >= 0; --k) {              // L^T x = z
    const double* uk = &u_[static_cast<std::size_t>(k) * w];
    const int len = std::min(n - 1, k + w) - k;
    const double far = x[k] - dot(uk + 1, x + k + 2, len - 1);
    x[k] = far - uk[0] * x[k + 1];
  }
}

}  // namespace fluidbed
