#pragma once
// The synthetic beds of the bubble analysis's tests: a packed hexagonal monolayer
// (synthetic_bed.hpp) with circular holes cut out, and the D_e the detector should see for them.
//
// The expected size of a hole, from the construction. Removing the spheres whose centres lie
// within the hole's radius plus one particle radius empties their cells of the hexagonal
// lattice: each sphere of a packed layer owns a hexagon of area sqrt(3)/2 d^2 whose edges pass
// through its contact points, that is through the rims of its neighbours, and what remains of
// the neighbours inside it are their rims' thin outer slivers. So the construction is, to the
// detector, void (eps = 1) over the union H of the removed hexagons and packed (eps_b = 0.3954)
// outside. The detector thresholds the void fraction over a 10 mm window centred on each 2 mm
// cell, 1 - (1 - f) (1 - eps_b) with f the share of the window in H: a cell is void when
// f > (0.8 - eps_b) / (1 - eps_b) = 0.669. expected_d_eq applies exactly that to H (f sampled on
// 20 x 20 points of each window; a point lies in H when its nearest lattice site was removed),
// independently of the detector's sphere volumes. For hole radii of 8 to 40 mm at 6 positions
// each the detected D_e agrees to within 2.7 % (4.5 % at 6 mm: a handful of boundary cells).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "analysis/bubbles.hpp"
#include "synthetic_bed.hpp"

namespace fluidbed::testing::bubble_bed {

inline constexpr double kD = 0.004;                    // m, particle diameter
inline constexpr double kWidth = 0.15;                 // m
inline constexpr double kTop = 0.2;                    // m, highest centre of the synthetic bed
inline const double kRow = std::sqrt(3.0) / 2.0 * kD;  // m, row spacing of the hexagonal layer

// True when the point's nearest site of hex_bed's lattice was removed by one of the holes.
inline bool in_removed_hexagon(double x, double y, const std::vector<Hole>& holes) {
  const double r = 0.5 * kD;
  const int row0 = static_cast<int>(std::lround((y - r) / kRow));
  double best = std::numeric_limits<double>::infinity(), sx = 0.0, sy = 0.0;
  for (int row = std::max(0, row0 - 1); row <= row0 + 1; ++row) {
    const double yr = r + row * kRow, shift = row % 2 == 1 ? r : 0.0;
    const int col0 = static_cast<int>(std::lround((x - r - shift) / kD));
    for (int col = col0 - 1; col <= col0 + 1; ++col) {
      const double xs = r + shift + col * kD;
      const double d2 = (xs - x) * (xs - x) + (yr - y) * (yr - y);
      if (d2 < best) {
        best = d2;
        sx = xs;
        sy = yr;
      }
    }
  }
  for (const Hole& h : holes)
    if (std::hypot(sx - h.x, sy - h.y) < h.radius + r) return true;
  return false;
}

// D_e of the void the detector should see for these holes (see the top of this file), on its
// grid of 2 mm cells with a window of 10 mm and the threshold 0.8.
inline double expected_d_eq(const std::vector<Hole>& holes) {
  constexpr double cell = 0.002, window = 0.01;
  constexpr int n = 20;  // samples per window side
  const double eps_b = 1.0 - std::numbers::pi / (2.0 * std::sqrt(3.0)) * 2.0 / 3.0;
  const double f_void = (0.8 - eps_b) / (1.0 - eps_b);
  int cells = 0;
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 75; ++i) {
      const double cx = (i + 0.5) * cell, cy = (j + 0.5) * cell;
      bool near = false;
      for (const Hole& h : holes)
        near = near || std::hypot(cx - h.x, cy - h.y) < h.radius + kD + window;
      if (!near) continue;
      int in = 0;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          in += in_removed_hexagon(cx - 0.5 * window + (a + 0.5) * window / n,
                                   cy - 0.5 * window + (b + 0.5) * window / n, holes);
      if (in > f_void * n * n) ++cells;
    }
  return std::sqrt(4.0 * cells * cell * cell / std::numbers::pi);
}

inline const Bubble* find_id(const BubbleFrame& f, int id) {
  for (const Bubble& b : f.regions)
    if (b.id == id) return &b;
  return nullptr;
}

inline BubbleFrame one_frame(const Particles& p, const BubbleSettings& s = {},
                             const BedGeometry& g = {}) {
  BubbleAnalysis a(s, g);
  return a.analyse(0.01, p);
}

}  // namespace fluidbed::testing::bubble_bed

// The names both bubble test files use (test_bubbles.cpp, test_bubble_detection.cpp).
using fluidbed::BedGeometry;
using fluidbed::Bubble;
using fluidbed::BubbleAnalysis;
using fluidbed::BubbleEvent;
using fluidbed::BubbleFrame;
using fluidbed::BubbleHistory;
using fluidbed::BubbleRow;
using fluidbed::BubbleSettings;
using fluidbed::Particles;
using fluidbed::Regime;
using fluidbed::testing::hex_bed;
using fluidbed::testing::Hole;
using namespace fluidbed::testing::bubble_bed;
