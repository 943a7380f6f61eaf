#pragma once
// The paper's packing start (section 3, Fig. 5): square cells one diameter wide over the container,
// alternate rows shifted by a radius. Pure geometry, shared by placement and validation.
#include <cmath>
#include <vector>

namespace fluidbed {

struct LatticeSite {
  double x, y;  // m, cell centre
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
