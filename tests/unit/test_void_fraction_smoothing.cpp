// The smoothed void fraction (coupling/void_fraction_smoothing.hpp): s - L^2 laplacian(s) = s0
// with no flux through the walls, against a hand solution, its discrete kernel, and the total it
// must keep (the scene keys that choose it: test_scene.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "cfd/gas_grid.hpp"
#include "coupling/void_fraction_smoothing.hpp"

using namespace fluidbed;

namespace {

GasGrid smoothing_grid(int nx, int ny, double width, double height) {
  GasGrid g;
  g.nx = nx;
  g.ny = ny;
  g.width = width;
  g.height = height;
  return g;
}

double total_of(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

}  // namespace

TEST(VoidFractionSmoothing, ThreeByThreeCellsByHand) {
  // 3 x 3 cells of 1 cm, L = 1 cm (a = L^2 / dx^2 = 1), a volume of 7 in the centre cell. By
  // symmetry: the centre c, the four edge cells e, the four corners k, with
  //   corner (two neighbours): 3 k - 2 e = 0          -> k = 2 e / 3
  //   edge (three neighbours): 4 e - c - 2 k = 0      -> e = 3 c / 8
  //   centre (four):           5 c - 4 e = 7          -> c = 2, e = 0.75, k = 0.5,
  // and c + 4 e + 4 k = 7: the total kept.
  const GasGrid g = smoothing_grid(3, 3, 0.03, 0.03);
  const VoidFractionSmoother smooth(g, 0.01);
  std::vector<double> v(9, 0.0);
  v[4] = 7.0;
  smooth.apply(v);
  const double expected[9] = {0.5, 0.75, 0.5, 0.75, 2.0, 0.75, 0.5, 0.75, 0.5};
  for (int c = 0; c < 9; ++c) EXPECT_NEAR(v[c], expected[c], 1e-14) << c;
}

TEST(VoidFractionSmoothing, KeepsTheTotalAndAUniformField) {
  // Both orientations of the band (nx < ny: along x; nx > ny: the grid renumbered along y), on
  // cells that are not square.
  for (const auto& [nx, ny] : {std::pair{7, 23}, std::pair{23, 7}}) {
    const GasGrid g = smoothing_grid(nx, ny, 0.09, 0.5);
    const VoidFractionSmoother smooth(g, 0.004);
    std::vector<double> v(static_cast<std::size_t>(g.cells()));
    for (std::size_t c = 0; c < v.size(); ++c) v[c] = std::fmod(0.37 * static_cast<double>(c * c), 1.0);
    const double before = total_of(v);
    smooth.apply(v);
    EXPECT_NEAR(total_of(v), before, 1e-13 * before) << nx << " x " << ny;
    std::vector<double> uniform(v.size(), 0.25);
    smooth.apply(uniform);
    for (const double u : uniform) ASSERT_NEAR(u, 0.25, 1e-15) << nx << " x " << ny;
  }
}

TEST(VoidFractionSmoothing, BothOrientationsGiveTheSameField) {
  // The same field on a grid and on its transpose (x and y exchanged): the same values.
  const GasGrid tall = smoothing_grid(5, 19, 0.05, 0.38), wide = smoothing_grid(19, 5, 0.38, 0.05);
  const VoidFractionSmoother a(tall, 0.007), b(wide, 0.007);
  std::vector<double> v(95), w(95);
  for (int j = 0; j < 19; ++j)
    for (int i = 0; i < 5; ++i) v[j * 5 + i] = w[i * 19 + j] = 1.0 + std::sin(i + 3.0 * j);
  a.apply(v);
  b.apply(w);
  for (int j = 0; j < 19; ++j)
    for (int i = 0; i < 5; ++i) ASSERT_NEAR(v[j * 5 + i], w[i * 19 + j], 1e-14) << i << ", " << j;
}

TEST(VoidFractionSmoothing, APointSpreadsAsTheDiscreteKernel) {
  // A line of volume across the width (uniform in x) at the middle of a tall column: away from
  // the walls, s_j - a (s_{j+1} - 2 s_j + s_{j-1}) = 0 is solved by s_j = s_0 r^|j| with
  // a r^2 - (1 + 2 a) r + a = 0, r = (1 + 2a - sqrt(1 + 4a)) / (2a): the discrete form of
  // exp(-|y| / L) (a = 4: r = 0.6096, exp(-1/2) = 0.6065).
  const int ny = 201;
  const double dy = 0.001, L = 2.0 * dy;
  const GasGrid g = smoothing_grid(3, ny, 0.003, ny * dy);
  const VoidFractionSmoother smooth(g, L);
  std::vector<double> v(static_cast<std::size_t>(g.cells()), 0.0);
  for (int i = 0; i < 3; ++i) v[100 * 3 + i] = 1.0;
  smooth.apply(v);
  const double a = L * L / (dy * dy);
  const double r = (1.0 + 2.0 * a - std::sqrt(1.0 + 4.0 * a)) / (2.0 * a);
  for (int j = 100; j < 130; ++j) {
    EXPECT_NEAR(v[(j + 1) * 3] / v[j * 3], r, 1e-12) << j;
    EXPECT_NEAR(v[(200 - j - 1) * 3], v[(j + 1) * 3], 1e-16) << j;  // symmetric about the middle
    EXPECT_NEAR(v[j * 3 + 1], v[j * 3], 1e-16);                       // still uniform across
  }
  // The peak: 1 / sqrt(1 + 4 a) of the line's volume per cell (sum of s_0 r^|j| = 1).
  EXPECT_NEAR(v[100 * 3], 1.0 / std::sqrt(1.0 + 4.0 * a), 1e-12);
}
