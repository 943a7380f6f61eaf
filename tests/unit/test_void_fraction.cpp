// The fine void-fraction grid (model.md 6): exact sphere shares per cell against an independent
// quadrature of the sphere's depth over the cell, conservation at walls and corners, and the
// packing limit of a hexagonal layer.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "analysis/void_fraction.hpp"
#include "core/errors.hpp"
#include "core/random.hpp"
#include "synthetic_bed.hpp"

using fluidbed::add_sphere_to_fine_grid;
using fluidbed::compute_void_fraction;
using fluidbed::FineGrid;
using fluidbed::InputError;
using fluidbed::make_fine_grid;
using fluidbed::make_void_fraction_field;
using fluidbed::VoidFractionField;

namespace {

constexpr double kRadius = 0.002;  // m, the paper's particle radius
const double kSphereVolume = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;

FineGrid paper_grid() {
  return make_fine_grid(0.15, 0.9, 0.004, 0.002, 0.004);
}

// The volume of the sphere (centre (x, y), radius R) above the rectangle [x0, x1] x [y0, y1]:
// the integral of its depth 2 sqrt(R^2 - rho^2) by the midpoint rule on n x n points. The depth
// has a square-root edge at the rim, so the error falls as n^-1.5: about 1e-5 of the sphere's
// volume at n = 1200 here, far below the tolerances used.
double quadrature_share(double x, double y, double R, double x0, double x1, double y0, double y1,
                        int n = 1200) {
  double s = 0.0;
  const double hx = (x1 - x0) / n, hy = (y1 - y0) / n;
  for (int a = 0; a < n; ++a) {
    const double u = x0 + (a + 0.5) * hx - x;
    for (int b = 0; b < n; ++b) {
      const double v = y0 + (b + 0.5) * hy - y;
      const double r2 = R * R - u * u - v * v;
      if (r2 > 0.0) s += 2.0 * std::sqrt(r2);
    }
  }
  return s * hx * hy;
}

}  // namespace

TEST(VoidFraction, GridCoversTheDomainWithCellsOfHalfADiameter) {
  const FineGrid g = paper_grid();
  EXPECT_EQ(g.nx, 75);
  EXPECT_EQ(g.ny, 450);
  EXPECT_DOUBLE_EQ(g.width(), 0.15);
  EXPECT_NEAR(g.height(), 0.9, 1e-15);
  // A cell size that does not divide the width: cells stretched to cover it exactly.
  const FineGrid h = make_fine_grid(0.15, 0.9, 0.004, 0.0023, 0.004);
  EXPECT_EQ(h.nx, 65);
  EXPECT_NEAR(h.nx * h.dx, 0.15, 1e-15);
  EXPECT_NEAR(h.dx, 0.0023, 0.0023 * 0.03);
}

TEST(VoidFraction, SharesMatchQuadratureOfTheSphere) {
  const FineGrid g = paper_grid();
  // Centres: inside a cell's middle (3 x 3 cells), on a grid line, near a corner of four cells.
  const double centres[][2] = {
      {0.051, 0.101}, {0.0500, 0.1013}, {0.0503, 0.1007}, {0.0517, 0.0994}};
  for (const auto& c : centres) {
    std::vector<double> solid(static_cast<std::size_t>(g.cells()), 0.0);
    add_sphere_to_fine_grid(g, c[0], c[1], kRadius, solid);
    const int i0 = static_cast<int>((c[0] - kRadius) / g.dx),
              j0 = static_cast<int>((c[1] - kRadius) / g.dy);
    double sum = 0.0;
    for (int j = j0; j <= j0 + 3; ++j)
      for (int i = i0; i <= i0 + 3; ++i) {
        const double expected = quadrature_share(c[0], c[1], kRadius, i * g.dx, (i + 1) * g.dx,
                                                 j * g.dy, (j + 1) * g.dy);
        EXPECT_NEAR(solid[g.index(i, j)], expected, 2e-4 * kSphereVolume)
            << "cell " << i << "," << j;
        sum += solid[g.index(i, j)];
      }
    EXPECT_NEAR(sum, kSphereVolume, 1e-13 * kSphereVolume);
  }
}

TEST(VoidFraction, SharesSumToTheSphereAtWallsCornersAndOutside) {
  const FineGrid g = paper_grid();
  fluidbed::SplitMix64 rng(7);
  for (int k = 0; k < 500; ++k) {
    // Anywhere, including overlapping a wall and centres a little outside the domain.
    const double x = -0.003 + 0.156 * rng.uniform();
    const double y = -0.003 + 0.906 * rng.uniform();
    std::vector<double> solid(static_cast<std::size_t>(g.cells()), 0.0);
    add_sphere_to_fine_grid(g, x, y, kRadius, solid);
    double sum = 0.0;
    for (double v : solid) {
      EXPECT_GT(v, -1e-15 * kSphereVolume);
      sum += v;
    }
    ASSERT_NEAR(sum, kSphereVolume, 1e-12 * kSphereVolume) << "at " << x << ", " << y;
  }
  // A sphere overlapping the left wall by 1 mm: the part beyond the wall stays in column 0.
  std::vector<double> solid(static_cast<std::size_t>(g.cells()), 0.0);
  add_sphere_to_fine_grid(g, 0.001, 0.101, kRadius, solid);
  double column1 = 0.0, column0 = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    column0 += solid[g.index(0, j)];
    column1 += solid[g.index(1, j)];
  }
  EXPECT_NEAR(column1, quadrature_share(0.001, 0.101, kRadius, 0.002, 0.004, 0.098, 0.104),
              2e-4 * kSphereVolume);
  EXPECT_NEAR(column0 + column1, kSphereVolume, 1e-13 * kSphereVolume);
}

TEST(VoidFraction, PackedHexagonalLayerSitsAtItsPackingLimit) {
  // Touching spheres in a hexagonal layer fill 0.9069 of the plane and 2/3 of the slab's depth:
  // eps = 1 - 0.9069 x 2/3 = 0.3954 (model.md 6). Averaged over a window 40 mm wide, 40 mm high,
  // away from walls and the surface, the mean is that to within the window's edge (about one
  // row of cells out of 20: 0.01).
  VoidFractionField f = make_void_fraction_field(paper_grid(), 0.01);
  const auto p = fluidbed::testing::hex_bed(0.15, 0.2);
  compute_void_fraction(p, f);
  double sum = 0.0;
  int n = 0;
  for (int j = 30; j < 50; ++j)
    for (int i = 20; i < 40; ++i) {
      sum += f.at(i, j);
      ++n;
    }
  const double packing = 1.0 - std::numbers::pi / (2.0 * std::sqrt(3.0)) * 2.0 / 3.0;
  EXPECT_NEAR(sum / n, packing, 0.01);
  // The total solid is every sphere's volume (no share lost).
  double solid = 0.0;
  for (double e : f.eps) solid += (1.0 - e) * f.grid.cell_area() * f.grid.thickness;
  EXPECT_NEAR(solid, static_cast<double>(p.size()) * kSphereVolume,
              1e-9 * static_cast<double>(p.size()) * kSphereVolume);
  // Above the bed: nothing; top_row is one past the highest row a sphere reaches.
  const double top = *std::max_element(p.y.begin(), p.y.end()) + kRadius;
  EXPECT_EQ(f.top_row, static_cast<int>(top / f.grid.dy) + 1);
  for (int i = 0; i < f.grid.nx; ++i) EXPECT_EQ(f.at(i, f.top_row), 1.0);
}

TEST(VoidFraction, WindowAverageIsTheExactVolumeFractionOfTheWindow) {
  // The window (10 mm, 5 cells) is the exact solid volume of the spheres in a 10 x 10 mm square
  // around each cell's centre, clipped at the walls: checked against the quadrature of each
  // sphere's depth over that square, for a few spheres near a wall and the bottom.
  VoidFractionField f = make_void_fraction_field(paper_grid(), 0.01);
  EXPECT_EQ(f.half_window_x, 2);
  EXPECT_EQ(f.half_window_y, 2);
  EXPECT_EQ(make_void_fraction_field(paper_grid(), 0.006).half_window_x, 1);
  EXPECT_EQ(make_void_fraction_field(paper_grid(), 0.0).half_window_x, 0);
  const auto p = fluidbed::testing::hex_bed(0.012, 0.01);  // a corner of a bed: 9 spheres
  fluidbed::Particles q;
  q.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    q.x[i] = p.x[i];
    q.y[i] = p.y[i];
    q.set_sphere(i, 0.004, 2700.0);
  }
  compute_void_fraction(q, f);
  for (const auto& ij : {std::array<int, 2>{0, 0}, {1, 2}, {3, 3}, {6, 1}, {4, 7}}) {
    const int i = ij[0], j = ij[1];
    const double x0 = std::max(0.0, (i - 2) * 0.002), x1 = (i + 3) * 0.002;
    const double y0 = std::max(0.0, (j - 2) * 0.002), y1 = (j + 3) * 0.002;
    double solid = 0.0;
    for (std::size_t k = 0; k < q.size(); ++k)
      solid += quadrature_share(q.x[k], q.y[k], kRadius, x0, x1, y0, y1, 400);
    EXPECT_NEAR(f.window_at(i, j), 1.0 - solid / ((x1 - x0) * (y1 - y0) * 0.004), 2e-4)
        << "cell " << i << "," << j;
  }
  // The packed layer through the window: its mean, with a spread far below the single cells'
  // (which see the gaps between spheres).
  VoidFractionField g = make_void_fraction_field(paper_grid(), 0.01);
  compute_void_fraction(fluidbed::testing::hex_bed(0.15, 0.2), g);
  double sum = 0.0, sum2 = 0.0, cell_sum2 = 0.0;
  int n = 0;
  for (int j = 30; j < 50; ++j)
    for (int i = 20; i < 40; ++i) {
      sum += g.window_at(i, j);
      sum2 += g.window_at(i, j) * g.window_at(i, j);
      cell_sum2 += g.at(i, j) * g.at(i, j);
      ++n;
    }
  const double mean = sum / n;
  const double packing = 1.0 - std::numbers::pi / (2.0 * std::sqrt(3.0)) * 2.0 / 3.0;
  EXPECT_NEAR(mean, packing, 0.01);
  const double window_spread = std::sqrt(sum2 / n - mean * mean);
  const double cell_spread = std::sqrt(cell_sum2 / n - mean * mean);
  EXPECT_LT(window_spread, 0.2 * cell_spread);  // 0.006 against 0.047
  // Rows well above the bed: 1.
  EXPECT_EQ(g.window_at(10, g.top_row + 2), 1.0);
  try {
    make_void_fraction_field(paper_grid(), -0.01);
    ADD_FAILURE() << "no error for a negative window";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("bubbles.window ", 0), 0u) << e.what();
  }
}

TEST(VoidFraction, BadCellSizeIsAnInputErrorNamingTheKey) {
  for (double bad : {0.0, -0.002, 0.0004, 1.0}) {
    try {
      make_fine_grid(0.15, 0.9, 0.004, bad, 0.004);
      ADD_FAILURE() << "no error for cell_size " << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bubbles.cell_size"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos);
    }
  }
}
