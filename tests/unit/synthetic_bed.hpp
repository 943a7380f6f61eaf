#pragma once
// Synthetic particle sets for the bubble, void-fraction and mixing tests: a packed hexagonal
// monolayer (the densest layer of spheres in the slab: eps = 1 - 0.9069 x 2/3 = 0.395) in the
// paper's domain, with circular holes cut out.
#include <cmath>
#include <vector>

#include "dem/particles.hpp"

namespace fluidbed::testing {

struct Hole {
  double x, y;    // m, centre
  double radius;  // m, particles whose centres lie closer than radius + d/2 are removed
};

// Rows of touching spheres of diameter d, rows sqrt(3)/2 d apart, odd rows shifted by d/2, from
// the bottom wall up to `top` (highest centre), across `width`; spheres of the holes removed.
inline Particles hex_bed(double width, double top, const std::vector<Hole>& holes = {},
                         double d = 0.004) {
  const double r = 0.5 * d;
  std::vector<double> xs, ys;
  for (int row = 0;; ++row) {
    const double y = r + row * d * std::sqrt(3.0) / 2.0;
    if (y > top + 1e-12) break;
    for (int col = 0;; ++col) {
      const double x = r + (row % 2 == 1 ? r : 0.0) + col * d;
      if (x + r > width + 1e-12) break;
      bool removed = false;
      for (const Hole& h : holes)
        if (std::hypot(x - h.x, y - h.y) < h.radius + r) removed = true;
      if (removed) continue;
      xs.push_back(x);
      ys.push_back(y);
    }
  }
  Particles p;
  p.resize(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    p.x[i] = xs[i];
    p.y[i] = ys[i];
    p.set_sphere(i, d, 2700.0);
  }
  return p;
}

}  // namespace fluidbed::testing
