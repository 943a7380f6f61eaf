#include "analysis/mixing.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace fluidbed {

std::vector<std::uint8_t> kinds_by_initial_height(const std::vector<double>& y) {
  std::vector<std::size_t> order(y.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return y[a] < y[b] || (y[a] == y[b] && a < b); });
  std::vector<std::uint8_t> kind(y.size(), 1);
  for (std::size_t k = 0; k < y.size() / 2; ++k) kind[order[k]] = 0;
  return kind;
}

LaceyResult lacey_index(const Particles& p, const std::vector<std::uint8_t>& kind, double width,
                        double height, const LaceySettings& s) {
  if (!(s.cell_size > 0.0) || s.cell_size > std::min(width, height)) {
    std::ostringstream os;
    os << "mixing.cell_size must be positive and fit the domain (got " << s.cell_size << " m)";
    throw InputError(os.str());
  }
  if (s.min_particles < 1) {
    std::ostringstream os;
    os << "mixing.min_particles must be at least 1 (got " << s.min_particles << ")";
    throw InputError(os.str());
  }
  if (kind.size() != p.size())
    throw std::invalid_argument("lacey_index: one kind per particle expected");

  const int nx = std::max(1, static_cast<int>(std::lround(width / s.cell_size)));
  const int ny = std::max(1, static_cast<int>(std::lround(height / s.cell_size)));
  const double dx = width / nx, dy = height / ny;
  std::vector<int> count(static_cast<std::size_t>(nx * ny), 0), ones(count.size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int ci = std::clamp(static_cast<int>(std::floor(p.x[i] / dx)), 0, nx - 1);
    const int cj = std::clamp(static_cast<int>(std::floor(p.y[i] / dy)), 0, ny - 1);
    const auto c = static_cast<std::size_t>(ci + nx * cj);
    ++count[c];
    ones[c] += kind[i] != 0 ? 1 : 0;
  }
  LaceyResult r;
  long total = 0, total_ones = 0;
  for (std::size_t c = 0; c < count.size(); ++c) {
    if (count[c] < s.min_particles) continue;
    ++r.cells;
    total += count[c];
    total_ones += ones[c];
  }
  if (r.cells == 0) return r;
  r.particles = static_cast<int>(total);
  r.p = static_cast<double>(total_ones) / static_cast<double>(total);
  r.mean_per_cell = static_cast<double>(total) / r.cells;
  double s2 = 0.0;
  for (std::size_t c = 0; c < count.size(); ++c) {
    if (count[c] < s.min_particles) continue;
    const double x = static_cast<double>(ones[c]) / count[c];
    s2 += count[c] * (x - r.p) * (x - r.p);
  }
  r.s2 = s2 / static_cast<double>(total);
  r.s0_2 = r.p * (1.0 - r.p);
  r.sr_2 = r.s0_2 / r.mean_per_cell;
  // One kind only, or one particle per cell on average: M is undefined.
  if (!(r.s0_2 - r.sr_2 > 0.0)) return r;
  r.index = (r.s0_2 - r.s2) / (r.s0_2 - r.sr_2);
  r.ok = true;
  return r;
}

}  // namespace fluidbed
