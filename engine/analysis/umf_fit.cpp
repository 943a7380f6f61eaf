#include "analysis/umf_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fluidbed {

UmfFit fit_umf(std::vector<double> u, std::vector<double> dp) {
  UmfFit best;
  const std::size_t n = std::min(u.size(), dp.size());
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return u[a] < u[b]; });
  std::vector<double> us(n), ps(n);
  for (std::size_t k = 0; k < n; ++k) {
    us[k] = u[order[k]];
    ps[k] = dp[order[k]];
  }
  if (n < 4) {
    best.why = "needs at least 4 points on the decreasing branch";
    return best;
  }
  double best_sse = std::numeric_limits<double>::infinity();
  for (std::size_t split = 2; split + 2 <= n; ++split) {
    // Line through the low part.
    double su = 0, sp = 0, suu = 0, sup = 0;
    for (std::size_t k = 0; k < split; ++k) {
      su += us[k];
      sp += ps[k];
      suu += us[k] * us[k];
      sup += us[k] * ps[k];
    }
    const double m = static_cast<double>(split);
    const double den = m * suu - su * su;
    if (!(std::fabs(den) > 0.0)) continue;
    const double slope = (m * sup - su * sp) / den;
    const double intercept = (sp - slope * su) / m;
    double sse = 0.0;
    for (std::size_t k = 0; k < split; ++k) {
      const double r = ps[k] - (intercept + slope * us[k]);
      sse += r * r;
    }
    // Plateau over the high part.
    double plateau = 0.0;
    for (std::size_t k = split; k < n; ++k) plateau += ps[k];
    plateau /= static_cast<double>(n - split);
    for (std::size_t k = split; k < n; ++k) sse += (ps[k] - plateau) * (ps[k] - plateau);
    if (sse < best_sse && slope > 0.0) {
      best_sse = sse;
      best.ok = true;
      best.slope = slope;
      best.intercept = intercept;
      best.plateau = plateau;
      best.umf = (plateau - intercept) / slope;
      best.low_points = static_cast<int>(split);
      best.high_points = static_cast<int>(n - split);
    }
  }
  if (!best.ok) {
    best.why = "no split gives a rising defluidization line";
    return best;
  }
  best.rms_residual = std::sqrt(best_sse / static_cast<double>(n));
  return best;
}

}  // namespace fluidbed
