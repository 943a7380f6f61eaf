// Porosity (eq 22): exact sphere shares per cell against textbook caps and an independent
// nested Gauss-Legendre quadrature of the sphere over a quadrant.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "cfd/gas_grid.hpp"
#include "coupling/porosity.hpp"

using fluidbed::add_particle_volume;
using fluidbed::GasGrid;
using fluidbed::porosity_from_solid;
using fluidbed::sphere_cap_volume;
using fluidbed::sphere_quadrant_volume;

namespace {

constexpr double kSphereR = 0.002;  // m, the paper's particle radius
const double kSphereV = 4.0 / 3.0 * std::numbers::pi * kSphereR * kSphereR * kSphereR;

// Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n, the textbook recurrence).
struct Gauss {
  static constexpr int n = 48;
  std::array<double, n> u{}, w{};
  Gauss() {
    for (int k = 0; k < n; ++k) {
      double x = std::cos(std::numbers::pi * (k + 0.75) / (n + 0.5));
      double dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = x;
        for (int m = 2; m <= n; ++m) {
          const double p2 = ((2.0 * m - 1.0) * x * p1 - (m - 1.0) * p0) / m;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);
        const double step = p1 / dp;
        x -= step;
        if (std::fabs(step) < 1e-16) break;
      }
      u[k] = 0.5 * (1.0 + x);
      w[k] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2 / ((1 - x^2) P'^2), halved for [0, 1]
    }
  }
};
const Gauss kGauss;

// The volume of the sphere (radius R, at the origin) in x > a, y > b by nested quadrature of the
// sphere's definition: outer over x, inner over y = r sin(phi) of the chord length
// 2 sqrt(r^2 - y^2) = 2 r cos(phi) (dy = r cos(phi) dphi: an entire integrand). The outer
// integrand has (x - x_k)^(3/2) kinks where y = b meets the circle; the outer interval is split
// there and mapped by x = x0 + (x1 - x0)(3u^2 - 2u^3), which makes it smooth at both ends.
double quadrature_quadrant(double R, double a, double b) {
  const auto inner = [&](double x) {
    const double r2 = R * R - x * x;
    if (r2 <= 0.0) return 0.0;
    const double r = std::sqrt(r2);
    const double y0 = std::max(b, -r);
    if (y0 >= r) return 0.0;
    const double phi0 = std::asin(y0 / r);
    const double span = 0.5 * std::numbers::pi - phi0;
    double s = 0.0;
    for (int k = 0; k < Gauss::n; ++k) {
      const double c = std::cos(phi0 + span * kGauss.u[k]);
      s += kGauss.w[k] * 2.0 * r2 * c * c;
    }
    return s * span;
  };
  std::vector<double> cuts{std::max(a, -R), R};
  if (std::fabs(b) < R) {
    const double c = std::sqrt(R * R - b * b);
    for (double p : {-c, c}) {
      if (p > cuts.front() && p < R) cuts.insert(cuts.end() - 1, p);
    }
  }
  double total = 0.0;
  for (std::size_t m = 0; m + 1 < cuts.size(); ++m) {
    const double x0 = cuts[m], x1 = cuts[m + 1];
    if (x1 <= x0) continue;
    for (int k = 0; k < Gauss::n; ++k) {
      const double u = kGauss.u[k];
      const double x = x0 + (x1 - x0) * u * u * (3.0 - 2.0 * u);
      total += kGauss.w[k] * 6.0 * u * (1.0 - u) * (x1 - x0) * inner(x);
    }
  }
  return total;
}

double textbook_cap(double R, double h) {
  return std::numbers::pi * h * h * (3.0 * R - h) / 3.0;
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

int count_nonzero(const std::vector<double>& v) {
  int n = 0;
  for (double x : v) n += x != 0.0;
  return n;
}

}  // namespace

TEST(PorosityQuadrature, ReproducesSphereAndCaps) {
  // The test's own integrator, checked where the answer is textbook: its resolution is about
  // 1e-15 of the sphere, which justifies the 1e-12 tolerances of the comparisons below.
  EXPECT_NEAR(quadrature_quadrant(kSphereR, -2 * kSphereR, -2 * kSphereR), kSphereV,
              1e-14 * kSphereV);
  EXPECT_NEAR(quadrature_quadrant(kSphereR, 0.0, 0.0), kSphereV / 4, 1e-14 * kSphereV);
  for (double h : {0.1e-3, 0.7e-3, 1.5e-3, 2.9e-3}) {
    EXPECT_NEAR(quadrature_quadrant(kSphereR, kSphereR - h, -kSphereR), textbook_cap(kSphereR, h),
                1e-14 * kSphereV);
    EXPECT_NEAR(quadrature_quadrant(kSphereR, -kSphereR, kSphereR - h), textbook_cap(kSphereR, h),
                1e-14 * kSphereV);
  }
}

TEST(PorosityCap, TextbookValuesAndLimits) {
  EXPECT_DOUBLE_EQ(sphere_cap_volume(kSphereR, kSphereR), 0.0);
  EXPECT_DOUBLE_EQ(sphere_cap_volume(kSphereR, 3 * kSphereR), 0.0);
  EXPECT_DOUBLE_EQ(sphere_cap_volume(kSphereR, -kSphereR), kSphereV);
  EXPECT_DOUBLE_EQ(sphere_cap_volume(kSphereR, -5 * kSphereR), kSphereV);
  EXPECT_NEAR(sphere_cap_volume(kSphereR, 0.0), kSphereV / 2, 1e-15 * kSphereV);
  for (double a : {-1.9e-3, -1.0e-3, -0.3e-3, 0.2e-3, 1.2e-3, 1.99e-3}) {
    // h = R - a; cap + opposite cap = sphere.
    EXPECT_NEAR(sphere_cap_volume(kSphereR, a), textbook_cap(kSphereR, kSphereR - a),
                1e-13 * textbook_cap(kSphereR, kSphereR - a));
    EXPECT_NEAR(sphere_cap_volume(kSphereR, a) + sphere_cap_volume(kSphereR, -a), kSphereV,
                1e-15 * kSphereV);
  }
}

TEST(PorosityDoubleCap, SpecialValues) {
  // A quarter sphere; half a cap when one plane goes through the centre; a cap when the other
  // plane misses the sphere; nothing beyond the sphere; the whole sphere.
  EXPECT_NEAR(sphere_quadrant_volume(kSphereR, 0.0, 0.0), kSphereV / 4, 1e-15 * kSphereV);
  EXPECT_NEAR(sphere_quadrant_volume(kSphereR, 0.8e-3, 0.0),
              0.5 * sphere_cap_volume(kSphereR, 0.8e-3), 1e-15 * kSphereV);
  EXPECT_NEAR(sphere_quadrant_volume(kSphereR, 0.0, -0.8e-3),
              0.5 * (kSphereV - sphere_cap_volume(kSphereR, 0.8e-3)), 1e-15 * kSphereV);
  EXPECT_DOUBLE_EQ(sphere_quadrant_volume(kSphereR, 0.8e-3, -kSphereR),
                   sphere_cap_volume(kSphereR, 0.8e-3));
  EXPECT_DOUBLE_EQ(sphere_quadrant_volume(kSphereR, -3 * kSphereR, -0.5e-3),
                   sphere_cap_volume(kSphereR, -0.5e-3));
  EXPECT_DOUBLE_EQ(sphere_quadrant_volume(kSphereR, 1.5e-3, 1.5e-3), 0.0);  // 1.5^2 + 1.5^2 > 2^2
  EXPECT_DOUBLE_EQ(sphere_quadrant_volume(kSphereR, kSphereR, -kSphereR), 0.0);
  EXPECT_DOUBLE_EQ(sphere_quadrant_volume(kSphereR, -kSphereR, -kSphereR), kSphereV);
  // Symmetric in a and b; the four quadrants of any corner sum to the sphere.
  EXPECT_DOUBLE_EQ(sphere_quadrant_volume(kSphereR, 0.3e-3, 1.1e-3),
                   sphere_quadrant_volume(kSphereR, 1.1e-3, 0.3e-3));
  for (double a : {-2.5e-3, -1.7e-3, -0.4e-3, 0.0, 0.6e-3, 1.3e-3, 2.0e-3}) {
    for (double b : {-2.1e-3, -1.2e-3, -0.1e-3, 0.5e-3, 1.6e-3, 2.4e-3}) {
      const double four =
          sphere_quadrant_volume(kSphereR, a, b) + sphere_quadrant_volume(kSphereR, -a, b) +
          sphere_quadrant_volume(kSphereR, a, -b) + sphere_quadrant_volume(kSphereR, -a, -b);
      EXPECT_NEAR(four, kSphereV, 1e-14 * kSphereV) << a << " " << b;
    }
  }
}

TEST(PorosityDoubleCap, MatchesNestedQuadratureForAllSigns) {
  // Corners inside and outside the equatorial disc, every sign, |a| and |b| beyond R. The
  // closed form's absolute error is a few 1e-15 of the sphere (terms of size R^3 cancel when
  // the quadrant holds a sliver), so: 1e-12 of the sphere everywhere, and 1e-12 of the value
  // itself wherever the value is at least 1e-3 of the sphere.
  const double vals[] = {-2.3e-3, -2.0e-3, -1.95e-3, -1.4e-3, -0.7e-3, -0.05e-3, 0.0,
                         0.05e-3, 0.7e-3,  1.4e-3,   1.95e-3, 2.0e-3,  2.3e-3};
  for (double a : vals) {
    for (double b : vals) {
      const double exact = sphere_quadrant_volume(kSphereR, a, b);
      const double numeric = quadrature_quadrant(kSphereR, a, b);
      EXPECT_NEAR(exact, numeric, 1e-12 * kSphereV) << "a = " << a << ", b = " << b;
      if (numeric > 1e-3 * kSphereV) {
        EXPECT_NEAR(exact, numeric, 1e-12 * numeric) << "a = " << a << ", b = " << b;
      }
    }
  }
}

TEST(PorosityCell, SphereInsideOneCellPutsItsWholeVolumeThere) {
  const GasGrid g;  // 15 x 45 cells of 10 mm x 20 mm
  std::vector<double> solid(g.cells(), 0.0);
  add_particle_volume(g, 0.035, 0.05, kSphereR, solid);  // column 3 (30-40 mm), row 2 (40-60 mm)
  EXPECT_DOUBLE_EQ(solid[g.index(3, 2)], kSphereV);
  EXPECT_EQ(count_nonzero(solid), 1);
  // Touching a line from inside (distance exactly R is not a cut).
  std::vector<double> touch(g.cells(), 0.0);
  add_particle_volume(g, 0.032, 0.05, kSphereR, touch);
  EXPECT_NEAR(touch[g.index(3, 2)], kSphereV, 1e-15 * kSphereV);
  EXPECT_NEAR(sum(touch), kSphereV, 1e-15 * kSphereV);
}

TEST(PorosityCell, AcrossAVerticalFaceTheSharesAreCaps) {
  const GasGrid g;
  // Centre 0.5 mm left of x = 40 mm: a cap of height h = 1.5 mm goes into column 4.
  std::vector<double> solid(g.cells(), 0.0);
  add_particle_volume(g, 0.0395, 0.05, kSphereR, solid);
  const double cap = textbook_cap(kSphereR, 1.5e-3);
  EXPECT_NEAR(solid[g.index(4, 2)], cap, 1e-12 * cap);
  EXPECT_NEAR(solid[g.index(3, 2)], kSphereV - cap, 1e-12 * (kSphereV - cap));
  EXPECT_NEAR(sum(solid), kSphereV, 1e-12 * kSphereV);
  EXPECT_EQ(count_nonzero(solid), 2);
  // Centre 1.2 mm right of x = 30 mm: a cap of height 0.8 mm goes into column 2.
  std::vector<double> left(g.cells(), 0.0);
  add_particle_volume(g, 0.0312, 0.05, kSphereR, left);
  const double cap2 = textbook_cap(kSphereR, 0.8e-3);
  EXPECT_NEAR(left[g.index(2, 2)], cap2, 1e-12 * cap2);
  EXPECT_NEAR(left[g.index(3, 2)], kSphereV - cap2, 1e-12 * (kSphereV - cap2));
  EXPECT_NEAR(sum(left), kSphereV, 1e-12 * kSphereV);
  EXPECT_EQ(count_nonzero(left), 2);
}

TEST(PorosityCell, AcrossAHorizontalFaceTheSharesAreCaps) {
  const GasGrid g;
  // Centre 0.3 mm above y = 60 mm (row 3): a cap of height 1.7 mm goes into row 2.
  std::vector<double> solid(g.cells(), 0.0);
  add_particle_volume(g, 0.075, 0.0603, kSphereR, solid);
  const double cap = textbook_cap(kSphereR, 1.7e-3);
  EXPECT_NEAR(solid[g.index(7, 2)], cap, 1e-12 * cap);
  EXPECT_NEAR(solid[g.index(7, 3)], kSphereV - cap, 1e-12 * (kSphereV - cap));
  EXPECT_NEAR(sum(solid), kSphereV, 1e-12 * kSphereV);
  // Centre 1.9 mm below y = 80 mm (row 3): a cap of height 0.1 mm goes into row 4.
  std::vector<double> up(g.cells(), 0.0);
  add_particle_volume(g, 0.075, 0.0781, kSphereR, up);
  const double cap2 = textbook_cap(kSphereR, 0.1e-3);
  EXPECT_NEAR(up[g.index(7, 4)], cap2, 1e-12 * cap2);
  EXPECT_NEAR(up[g.index(7, 3)], kSphereV - cap2, 1e-12 * (kSphereV - cap2));
  EXPECT_NEAR(sum(up), kSphereV, 1e-12 * kSphereV);
}

TEST(PorosityCell, AcrossACornerTheFourSharesMatchQuadrature) {
  const GasGrid g;
  // Corner at (40 mm, 60 mm). Each case: centre offset (ox, oy) from the corner; each cell's
  // share is the sphere's volume in that cell's quadrant relative to the centre, integrated
  // numerically (1e-15 resolution, see PorosityQuadrature).
  const double offsets[][2] = {{-0.7e-3, -1.1e-3}, {0.4e-3, -0.2e-3}, {1.3e-3, 0.9e-3},
                               {-1.6e-3, 0.5e-3},  {0.1e-3, 1.9e-3},  {-1.9e-3, -1.9e-3}};
  for (const auto& o : offsets) {
    const double x = 0.04 + o[0], y = 0.06 + o[1];
    std::vector<double> solid(g.cells(), 0.0);
    add_particle_volume(g, x, y, kSphereR, solid);
    // Quadrant of cell (i, j) seen from the centre: x > 0.04 - x for the right column, etc.
    const double ax = 0.04 - x, ay = 0.06 - y;
    const double right_top = quadrature_quadrant(kSphereR, ax, ay);
    const double left_top = quadrature_quadrant(kSphereR, -ax, ay);
    const double right_bottom = quadrature_quadrant(kSphereR, ax, -ay);
    const double left_bottom = quadrature_quadrant(kSphereR, -ax, -ay);
    EXPECT_NEAR(solid[g.index(4, 3)], right_top, 1e-12 * kSphereV) << o[0] << " " << o[1];
    EXPECT_NEAR(solid[g.index(3, 3)], left_top, 1e-12 * kSphereV) << o[0] << " " << o[1];
    EXPECT_NEAR(solid[g.index(4, 2)], right_bottom, 1e-12 * kSphereV) << o[0] << " " << o[1];
    EXPECT_NEAR(solid[g.index(3, 2)], left_bottom, 1e-12 * kSphereV) << o[0] << " " << o[1];
    EXPECT_NEAR(sum(solid), kSphereV, 1e-12 * kSphereV);
  }
}

TEST(PorosityCell, CentreOnACornerGivesFourQuarters) {
  const GasGrid g;
  for (int i : {1, 3, 7, 14}) {
    for (int j : {1, 3, 44}) {
      std::vector<double> solid(g.cells(), 0.0);
      add_particle_volume(g, i * g.dx(), j * g.dy(), kSphereR, solid);
      for (int ci : {i - 1, i}) {
        for (int cj : {j - 1, j})
          EXPECT_NEAR(solid[g.index(ci, cj)], kSphereV / 4, 1e-14 * kSphereV);
      }
      EXPECT_EQ(count_nonzero(solid), 4);
    }
  }
  // On a vertical line (not a corner): two halves.
  std::vector<double> half(g.cells(), 0.0);
  add_particle_volume(g, 5 * g.dx(), 0.05, kSphereR, half);
  EXPECT_NEAR(half[g.index(4, 2)], kSphereV / 2, 1e-14 * kSphereV);
  EXPECT_NEAR(half[g.index(5, 2)], kSphereV / 2, 1e-14 * kSphereV);
}

TEST(PorosityCell, PartBeyondAWallStaysInTheEdgeCell) {
  const GasGrid g;
  const double overlap = 1e-6;  // m, a small wall overlap
  const struct {
    double x, y;
    int i, j;
  } cases[] = {{kSphereR - overlap, 0.05, 0, 2},                // left wall
               {g.width - kSphereR + overlap, 0.05, 14, 2},     // right wall
               {0.075, kSphereR - overlap, 7, 0},               // bottom wall
               {0.075, g.height - kSphereR + overlap, 7, 44},   // top (open exit)
               {kSphereR - overlap, kSphereR - overlap, 0, 0},  // bottom-left corner
               {g.width - kSphereR + overlap, g.height - kSphereR, 14, 44}};
  for (const auto& c : cases) {
    std::vector<double> solid(g.cells(), 0.0);
    add_particle_volume(g, c.x, c.y, kSphereR, solid);
    EXPECT_DOUBLE_EQ(solid[g.index(c.i, c.j)], kSphereV) << c.x << " " << c.y;
    EXPECT_EQ(count_nonzero(solid), 1);
  }
  // At the left wall and across the horizontal line y = 40 mm: split in y only, caps as usual.
  std::vector<double> solid(g.cells(), 0.0);
  add_particle_volume(g, kSphereR - overlap, 0.0405, kSphereR, solid);
  const double cap = textbook_cap(kSphereR, 1.5e-3);
  EXPECT_NEAR(solid[g.index(0, 1)], cap, 1e-12 * cap);
  EXPECT_NEAR(solid[g.index(0, 2)], kSphereV - cap, 1e-12 * kSphereV);
  EXPECT_NEAR(sum(solid), kSphereV, 1e-12 * kSphereV);
}

TEST(PorosityField, PeriodicArrangementGivesUniformPorosity) {
  // 8 spheres per cell on a pattern with the cell's period (x = 2.5, 7.5 mm; y = 2.5, 7.5, 12.5,
  // 17.5 mm; 5 mm apart, so no overlaps), shifted by (2.1, 1.3) mm: spheres straddle faces and
  // corners, yet every interior cell holds exactly 8 spheres' worth by periodicity:
  //   eps = 1 - 8 (4/3 pi R^3) / (dx dy dz) = 1 - 8 * 3.35103e-8 / 8e-7 = 1 - 0.335103
  //       = 0.664897
  const GasGrid g;
  std::vector<double> solid(g.cells(), 0.0);
  int n = 0;
  for (int i = 0; i < g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      for (double px : {2.5e-3, 7.5e-3}) {
        for (double py : {2.5e-3, 7.5e-3, 12.5e-3, 17.5e-3}) {
          add_particle_volume(g, i * g.dx() + px + 2.1e-3, j * g.dy() + py + 1.3e-3, kSphereR,
                              solid);
          ++n;
        }
      }
    }
  }
  std::vector<double> eps;
  porosity_from_solid(g, solid, eps);
  ASSERT_EQ(eps.size(), static_cast<std::size_t>(g.cells()));
  const double expected = 1.0 - 8.0 * kSphereV / (0.01 * 0.02 * 0.004);
  EXPECT_NEAR(expected, 0.664897, 1e-6);
  for (int i = 1; i + 1 < g.nx; ++i) {
    for (int j = 1; j + 1 < g.ny; ++j) EXPECT_NEAR(eps[g.index(i, j)], expected, 1e-12);
  }
  EXPECT_NEAR(sum(solid), n * kSphereV, 1e-12 * n * kSphereV);
  // An empty grid has eps = 1 everywhere.
  std::vector<double> none(g.cells(), 0.0);
  porosity_from_solid(g, none, eps);
  for (double e : eps) EXPECT_EQ(e, 1.0);
}

// The coupler's vectorised geometry pass (whichever build the CPU takes: AVX-512, AVX2 or plain
// x86-64) gives each sphere the scalar function's shares to the bit: the same cells, the same
// volumes. Centres all over the paper's grid, walls and corners included.
TEST(PorosityCell, VectorisedGeometryGivesTheScalarSharesToTheBit) {
  const GasGrid g;
  constexpr std::size_t kN = 2053;
  std::vector<double> x(kN), y(kN), R(kN);
  for (std::size_t i = 0; i < kN; ++i) {
    x[i] = g.width * static_cast<double>((i * 2654435761u) % 10007) / 10006.0;
    y[i] = g.height * static_cast<double>((i * 40503u) % 9973) / 9972.0;
    R[i] = kSphereR * (0.5 + static_cast<double>(i % 5) * 0.25);
  }
  fluidbed::ShareGeometry geo;
  geo.resize(kN);
  fluidbed::share_geometry(g, kN, x.data(), y.data(), R.data(), geo);
  for (std::size_t i = 0; i < kN; ++i) {
    fluidbed::VolumeShares a, b;
    fluidbed::shares_from_geometry(g, geo, i, R[i], a);
    fluidbed::particle_volume_shares(g, x[i], y[i], R[i], b);
    ASSERT_EQ(a.count, b.count) << "sphere " << i;
    for (int k = 0; k < a.count; ++k) {
      EXPECT_EQ(a.cell[k], b.cell[k]) << "sphere " << i;
      EXPECT_EQ(a.volume[k], b.volume[k]) << "sphere " << i;
    }
  }
}
