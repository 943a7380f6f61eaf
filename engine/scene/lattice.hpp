#pragma once
// The paper's packing start (section 3, Fig. 5): square cells one diameter wide over the container,
// alternate rows shifted by a radius. Pure geometry, shared by placement and validation.
#include <cmath>
#include <cstddef>
#include <vector>

namespace fluidbed {

struct LatticeSite {
  double x, y;  // m, cell centre
};

// The lattice's shape without its sites: rows, and cells in even and odd rows (odd rows shifted
// right by d/2), so that a site is found from its number and a domain of any height costs nothing
// until a site is asked for. Sites are numbered row by row from the bottom, left to right.
struct LatticeShape {
  double d = 0.0, r = 0.0;
  long rows = 0, cols_even = 0, cols_odd = 0;

  LatticeShape(double width, double top, double diameter) : d(diameter), r(0.5 * diameter) {
    // Tolerance so that a sphere exactly touching a wall counts as fitting.
    const double eps = 1e-12 * d;
    // The largest count n with `first + (n - 1) d + r <= limit + eps`, from a closed-form guess
    // corrected by the exact test (the same arithmetic as the site positions).
    auto count = [&](double first, double limit) {
      auto fits = [&](long k) { return first + static_cast<double>(k) * d + r <= limit + eps; };
      if (!fits(0)) return 0L;
      long n = static_cast<long>(std::floor((limit + eps - first - r) / d)) + 1;
      while (n > 1 && !fits(n - 1)) --n;
      while (fits(n)) ++n;
      return n;
    };
    rows = count(r, top);
    cols_even = count(r, width);
    cols_odd = count(r + r, width);
  }

  std::size_t size() const {
    const long even_rows = (rows + 1) / 2, odd_rows = rows / 2;
    return static_cast<std::size_t>(even_rows * cols_even + odd_rows * cols_odd);
  }

  LatticeSite site(std::size_t k) const {
    const long pair = cols_even + cols_odd;
    const long index = static_cast<long>(k);
    long row = 2 * (index / pair), col = index % pair;
    if (col >= cols_even) col -= cols_even, ++row;
    const double shift = (row % 2 == 1) ? r : 0.0;
    return {r + shift + static_cast<double>(col) * d, r + static_cast<double>(row) * d};
  }
};

// Every cell centre whose sphere of diameter d fits inside width x height (rows from the bottom,
// odd rows shifted right by d/2), up to `top` (the height; a smaller value fills only the bottom).
inline std::vector<LatticeSite> lattice_sites(double width, double top, double d) {
  std::vector<LatticeSite> sites;
  const double r = 0.5 * d;
  // Tolerance so that a sphere exactly touching a wall counts as fitting.
  const double eps = 1e-12 * d;
  for (int row = 0;; ++row) {
    const double y = r + row * d;
    if (y + r > top + eps) break;
    const double shift = (row % 2 == 1) ? r : 0.0;
    for (int col = 0;; ++col) {
      const double x = r + shift + col * d;
      if (x + r > width + eps) break;
      sites.push_back({x, y});
    }
  }
  return sites;
}

}  // namespace fluidbed
