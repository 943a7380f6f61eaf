#include "analysis/packing_metrics.hpp"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <limits>
#include <vector>

namespace fluidbed {

PackingMetrics measure_packing(const Particles& p, double width, double thickness) {
  constexpr double kColumn = 0.01;  // m
  constexpr double kBottomSkip = 0.02, kTopSkip = 0.03;  // m
  constexpr double kPi = std::numbers::pi;
  const int columns = std::max(1, static_cast<int>(std::lround(width / kColumn)));
  std::vector<double> top(columns, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int c = std::clamp(static_cast<int>(p.x[i] / width * columns), 0, columns - 1);
    top[c] = std::max(top[c], p.y[i]);
  }
  double sum = 0.0;
  int used = 0;
  for (double t : top)
    if (std::isfinite(t)) {
      sum += t;
      ++used;
    }
  PackingMetrics m;
  m.bed_height = used > 0 ? sum / used : 0.0;
  const double lo = kBottomSkip, hi = m.bed_height - kTopSkip;
  if (hi > lo) {
    double volume = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.y[i] >= lo && p.y[i] <= hi) {
        const double r = p.radius[i];
        volume += 4.0 / 3.0 * kPi * r * r * r;
      }
    m.solid_fraction = volume / (width * thickness * (hi - lo));
  }
  return m;
}

double bed_top(const Particles& p) {
  if (p.size() == 0) return 0.0;
  return *std::max_element(p.y.begin(), p.y.end());
}

}  // namespace fluidbed
