#include "analysis/void_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/errors.hpp"
#include "coupling/porosity.hpp"

namespace fluidbed {

namespace {

// Cells a sphere spans in one direction at most: cell_size >= d / 8 gives 9 (a diameter of 8
// cells plus one cut); one more for safety against rounding at the ends.
constexpr int kMaxSpan = 10;

[[noreturn]] void bad_cell_size(const std::string& why, double v) {
  std::ostringstream os;
  os << "bubbles.cell_size " << why << " (got " << v << " m)";
  throw InputError(os.str());
}

}  // namespace

FineGrid make_fine_grid(double width, double height, double thickness, double cell_size,
                        double particle_diameter) {
  if (!(cell_size > 0.0)) bad_cell_size("must be positive", cell_size);
  if (cell_size > std::min(width, height)) bad_cell_size("must not exceed the domain", cell_size);
  if (cell_size < particle_diameter / 8.0)
    bad_cell_size("must be at least 1/8 of the particle diameter", cell_size);
  FineGrid g;
  g.nx = std::max(1, static_cast<int>(std::lround(width / cell_size)));
  g.ny = std::max(1, static_cast<int>(std::lround(height / cell_size)));
  g.dx = width / g.nx;
  g.dy = height / g.ny;
  g.thickness = thickness;
  return g;
}

void add_sphere_to_fine_grid(const FineGrid& g, double x, double y, double R,
                             std::vector<double>& solid) {
  const double volume = 4.0 / 3.0 * std::numbers::pi * R * R * R;
  // The columns and rows the sphere's bounding square touches, clamped to the grid: a part
  // beyond a wall (or a centre outside the domain) falls into the edge cells.
  const auto span = [](double lo, double hi, double h, int n, int& first, int& last) {
    first = std::clamp(static_cast<int>(std::floor(lo / h)), 0, n - 1);
    last = std::clamp(static_cast<int>(std::floor(hi / h)), 0, n - 1);
  };
  int i0, i1, j0, j1;
  span(x - R, x + R, g.dx, g.nx, i0, i1);
  span(y - R, y + R, g.dy, g.ny, j0, j1);
  if (i0 == i1 && j0 == j1) {  // wholly inside one cell
    solid[g.index(i0, j0)] += volume;
    return;
  }
  const int nc = std::min(i1 - i0 + 1, kMaxSpan);
  const int nr = std::min(j1 - j0 + 1, kMaxSpan);
  // Q(line k, line l) for the lines bounding the spanned cells, k = 0..nc and l = 0..nr, relative
  // to the centre. Line 0 is "no line" (-infinity: the first cell takes everything below its
  // upper line), line nc is +infinity (nothing lies beyond it): Q(-inf, -inf) is the sphere,
  // Q(a, -inf) a cap, Q(+inf, .) = 0.
  double q[(kMaxSpan + 1) * (kMaxSpan + 1)];
  const int stride = nr + 1;
  double a[kMaxSpan + 1], b[kMaxSpan + 1];
  for (int k = 1; k < nc; ++k) a[k] = (i0 + k) * g.dx - x;
  for (int l = 1; l < nr; ++l) b[l] = (j0 + l) * g.dy - y;
  for (int k = 0; k <= nc; ++k) {
    for (int l = 0; l <= nr; ++l) {
      double v;
      if (k == nc || l == nr) {
        v = 0.0;
      } else if (k == 0 && l == 0) {
        v = volume;
      } else if (k == 0) {
        v = sphere_cap_volume(R, b[l]);
      } else if (l == 0) {
        v = sphere_cap_volume(R, a[k]);
      } else {
        v = sphere_quadrant_volume(R, a[k], b[l]);
      }
      q[k * stride + l] = v;
    }
  }
  for (int c = 0; c < nc; ++c) {
    for (int r = 0; r < nr; ++r) {
      const double share = q[c * stride + r] - q[(c + 1) * stride + r] - q[c * stride + r + 1] +
                           q[(c + 1) * stride + r + 1];
      solid[g.index(i0 + c, j0 + r)] += share;
    }
  }
}

VoidFractionField make_void_fraction_field(const FineGrid& grid, double window) {
  if (!(window >= 0.0) || window > std::min(grid.width(), grid.height())) {
    std::ostringstream os;
    os << "bubbles.window must be between 0 and the domain's size (got " << window << " m)";
    throw InputError(os.str());
  }
  VoidFractionField f;
  f.grid = grid;
  f.half_window_x = std::max(0, static_cast<int>(std::lround((window / grid.dx - 1.0) / 2.0)));
  f.half_window_y = std::max(0, static_cast<int>(std::lround((window / grid.dy - 1.0) / 2.0)));
  return f;
}

void compute_void_fraction(const Particles& p, VoidFractionField& field) {
  const FineGrid& g = field.grid;
  // The solid volume is summed in place, then turned into eps.
  std::vector<double>& solid = field.eps;
  solid.assign(static_cast<std::size_t>(g.cells()), 0.0);
  int top = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double R = p.radius[i];
    add_sphere_to_fine_grid(g, p.x[i], p.y[i], R, solid);
    const int j = std::clamp(static_cast<int>(std::floor((p.y[i] + R) / g.dy)), 0, g.ny - 1);
    top = std::max(top, j + 1);
  }
  field.top_row = top;
  const double inv_dv = 1.0 / (g.cell_area() * g.thickness);
  for (double& v : solid) v = 1.0 - v * inv_dv;

  // The window average, separable: along x into scratch, then along y. Direct sums in a fixed
  // order (deterministic); rows whose window reaches no solid stay at 1.
  const int kx = field.half_window_x, ky = field.half_window_y;
  const std::vector<double>& eps = field.eps;
  std::vector<double>& out = field.eps_window;
  std::vector<double>& row = field.scratch;
  out.assign(eps.size(), 1.0);
  row.assign(eps.size(), 1.0);
  const int rows = std::min(g.ny, top + ky);
  for (int j = 0; j < std::min(g.ny, top); ++j)
    for (int i = 0; i < g.nx; ++i) {
      const int a = std::max(0, i - kx), b = std::min(g.nx - 1, i + kx);
      double s = 0.0;
      for (int q = a; q <= b; ++q) s += eps[static_cast<std::size_t>(g.index(q, j))];
      row[static_cast<std::size_t>(g.index(i, j))] = s / (b - a + 1);
    }
  for (int j = 0; j < rows; ++j) {
    const int a = std::max(0, j - ky), b = std::min(g.ny - 1, j + ky);
    for (int i = 0; i < g.nx; ++i) {
      double s = 0.0;
      for (int q = a; q <= b; ++q) s += row[static_cast<std::size_t>(g.index(i, q))];
      out[static_cast<std::size_t>(g.index(i, j))] = s / (b - a + 1);
    }
  }
}

}  // namespace fluidbed
