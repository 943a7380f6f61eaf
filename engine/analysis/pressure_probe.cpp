#include "analysis/pressure_probe.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed {
namespace {

// Where a coordinate falls between the centres along one side of n cells of size d: the lower
// centre's index and the weight of the upper one, clamped to the first and last centres.
struct Between {
  int lower;
  double upper_weight;
};
Between between_centres(double x, double d, int n) {
  const double s = std::clamp(x / d - 0.5, 0.0, n - 1.0);  // in centre spacings from the first
  const int lower = std::min(static_cast<int>(std::floor(s)), n - 2);
  return {lower, s - lower};
}

}  // namespace

double probe_pressure(const GasGrid& g, const std::vector<double>& p, double x, double y) {
  const Between i = between_centres(x, g.dx(), g.nx), j = between_centres(y - g.bottom, g.dy(), g.ny);
  const auto at = [&](int di, int dj) {
    return p[static_cast<std::size_t>(g.index(i.lower + di, j.lower + dj))];
  };
  const double below = (1.0 - i.upper_weight) * at(0, 0) + i.upper_weight * at(1, 0);
  const double above = (1.0 - i.upper_weight) * at(0, 1) + i.upper_weight * at(1, 1);
  const double here = (1.0 - j.upper_weight) * below + j.upper_weight * above;
  double outlet = 0.0;
  for (int c = g.index(0, g.ny - 1); c < g.cells(); ++c) outlet += p[static_cast<std::size_t>(c)];
  return here - outlet / g.nx;
}

}  // namespace fluidbed
