#include "coupling/porosity.hpp"

#include <cmath>
#include <numbers>

#include "core/simd.hpp"

namespace fluidbed {

namespace {
constexpr double kPi = std::numbers::pi;

double sphere_volume(double R) {
  return 4.0 / 3.0 * kPi * R * R * R;
}
}  // namespace

double sphere_cap_volume(double R, double a) {
  if (a >= R) return 0.0;
  if (a <= -R) return sphere_volume(R);
  const double h = R - a;                    // cap height
  return kPi / 3.0 * h * h * (2.0 * R + a);  // pi h^2 (3R - h) / 3
}

// Derivation of the double cap (a, b >= 0 first): integrate over x the area of the circular
// segment y > b of the cross-section, a disc of radius r = sqrt(R^2 - x^2):
//   V = int_a^c [ r^2 acos(b / r) - b sqrt(r^2 - b^2) ] dx,   c = sqrt(R^2 - b^2).
// The second term is elementary. For the first, integrate by parts with G = R^2 x - x^3 / 3 (so
// G' = r^2); acos(b / r) vanishes at x = c and its derivative is -b x / (r^2 sqrt(c^2 - x^2)).
// The remaining integrals are asin-type ones and int dx / ((R^2 - x^2) sqrt(c^2 - x^2)), which
// x = c sin(t) turns into atan(b tan(t) / R) / (b R). Collecting terms and writing each
// acos as an atan2 of the same triangle (acos(b / sqrt(R^2 - a^2)) = atan2(w, b), and
// pi/2 - atan(a b / (R w)) = atan2(R w, a b)) gives the formula in the header. It is symmetric
// in a and b, gives a quarter sphere at a = b = 0, half a cap at b = 0, and 0 at w = 0; the
// atan2 form also holds for negative a or b inside the disc (checked against quadrature).
double sphere_quadrant_volume(double R, double a, double b) {
  const double w2 = R * R - a * a - b * b;
  if (w2 > 0.0) {
    const double w = std::sqrt(w2);
    const double R2 = R * R;
    return (2.0 * R2 * R * std::atan2(R * w, a * b) - a * (3.0 * R2 - a * a) * std::atan2(w, b) -
            b * (3.0 * R2 - b * b) * std::atan2(w, a) + 2.0 * a * b * w) /
           3.0;
  }
  // The corner (a, b) lies outside the sphere's equatorial disc. Then within the sphere
  // x > a and y > b cannot both bind: x > a >= 0 forces |y| < |b|, and x < a < 0 with
  // y < b < 0 is outside the sphere.
  if (a >= 0.0 && b >= 0.0) return 0.0;
  if (a >= 0.0) return sphere_cap_volume(R, a);  // b < 0: y > b holds wherever x > a
  if (b >= 0.0) return sphere_cap_volume(R, b);  // a < 0: x > a holds wherever y > b
  return sphere_volume(R) - sphere_cap_volume(R, -a) - sphere_cap_volume(R, -b);
}

int particle_volume_shares(const GasGrid& g, double x, double y, double R, VolumeShares& out) {
  const double dx = g.dx();
  const double dy = g.dy();
  const int i = g.column(x);
  const int j = g.row(y);
  const int c = g.index(i, j);
  const double volume = sphere_volume(R);

  // The line the sphere crosses in each direction, if any and if it is not a wall: the step to
  // the neighbour cell and the distance from the centre to the line (> 0 while the centre is on
  // this side; a hair below 0 when rounding put the centre on the line's other side, which the
  // cap and quadrant formulas handle).
  int di = 0;
  double ax = 0.0;
  const double left = x - i * dx;
  const double right = (i + 1) * dx - x;
  if (left < R && i > 0) {
    di = -1;
    ax = left;
  } else if (right < R && i + 1 < g.nx) {
    di = 1;
    ax = right;
  }
  int dj = 0;
  double ay = 0.0;
  const double yg = y - g.bottom;  // from the grid's bottom
  const double below = yg - j * dy;
  const double above = (j + 1) * dy - yg;
  if (below < R && j > 0) {
    dj = -1;
    ay = below;
  } else if (above < R && j + 1 < g.ny) {
    dj = 1;
    ay = above;
  }

  if (di == 0 && dj == 0) {  // the usual case: the sphere lies inside one cell
    out.cell[0] = c;
    out.volume[0] = volume;
    return out.count = 1;
  }
  const int cx = c + di;         // the neighbour across the vertical line
  const int cy = c + dj * g.nx;  // the neighbour across the horizontal line
  if (dj == 0) {
    const double vx = sphere_cap_volume(R, ax);
    out.cell[0] = cx;
    out.volume[0] = vx;
    out.cell[1] = c;
    out.volume[1] = volume - vx;
    return out.count = 2;
  }
  if (di == 0) {
    const double vy = sphere_cap_volume(R, ay);
    out.cell[0] = cy;
    out.volume[0] = vy;
    out.cell[1] = c;
    out.volume[1] = volume - vy;
    return out.count = 2;
  }
  // Across a corner: the diagonal cell gets the double cap, each side neighbour its cap less the
  // double cap, the centre's cell the rest (inclusion-exclusion: the four sum to the sphere).
  const double vx = sphere_cap_volume(R, ax);
  const double vy = sphere_cap_volume(R, ay);
  const double vxy = sphere_quadrant_volume(R, ax, ay);
  out.cell[0] = cx + dj * g.nx;
  out.volume[0] = vxy;
  out.cell[1] = cx;
  out.volume[1] = vx - vxy;
  out.cell[2] = cy;
  out.volume[2] = vy - vxy;
  out.cell[3] = c;
  out.volume[3] = volume - vx - vy + vxy;
  return out.count = 4;
}

void ShareGeometry::resize(std::size_t n) {
  for (auto* v : {&cell, &step_x, &step_y}) v->resize(n);
  for (auto* v : {&a_x, &a_y, &cap_x, &cap_y}) v->resize(n);
}

namespace {

// sphere_cap_volume without branches (the same arithmetic; a cap of no line crossed is 0).
inline double cap_volume_select(double R, double a, bool crossed) {
  const double h = R - a;
  const double inside = kPi / 3.0 * h * h * (2.0 * R + a);
  const double v = a >= R ? 0.0 : (a <= -R ? sphere_volume(R) : inside);
  return crossed ? v : 0.0;
}

}  // namespace

FLUIDBED_SIMD_CLONES void share_geometry(const GasGrid& g, std::size_t n, const double* x,
                                         const double* y, const double* R, ShareGeometry& out) {
  const double dx = g.dx(), dy = g.dy(), bottom = g.bottom;
  const int nx = g.nx, ny = g.ny;
  int* cell = out.cell.data();
  int* sx = out.step_x.data();
  int* sy = out.step_y.data();
  double* ax = out.a_x.data();
  double* ay = out.a_y.data();
  double* cx = out.cap_x.data();
  double* cy = out.cap_y.data();
#pragma omp simd
  for (std::size_t k = 0; k < n; ++k) {
    const double r = R[k];
    const double yk = y[k] - bottom;  // from the grid's bottom
    const int i = GasGrid::along(x[k], dx, nx), j = GasGrid::along(yk, dy, ny);
    cell[k] = j * nx + i;
    const double left = x[k] - i * dx, right = (i + 1) * dx - x[k];
    const bool to_left = (left < r) & (i > 0);
    const bool to_right = !to_left & (right < r) & (i + 1 < nx);
    sx[k] = to_left ? -1 : (to_right ? 1 : 0);
    const double a = to_left ? left : (to_right ? right : 0.0);
    ax[k] = a;
    cx[k] = cap_volume_select(r, a, to_left | to_right);
    const double below = yk - j * dy, above = (j + 1) * dy - yk;
    const bool down = (below < r) & (j > 0);
    const bool up = !down & (above < r) & (j + 1 < ny);
    sy[k] = down ? -1 : (up ? 1 : 0);
    const double b = down ? below : (up ? above : 0.0);
    ay[k] = b;
    cy[k] = cap_volume_select(r, b, down | up);
  }
}

int shares_from_geometry(const GasGrid& g, const ShareGeometry& geo, std::size_t k, double R,
                         VolumeShares& out) {
  const int c = geo.cell[k], di = geo.step_x[k], dj = geo.step_y[k];
  const double volume = sphere_volume(R);
  if (di == 0 && dj == 0) {
    out.cell[0] = c;
    out.volume[0] = volume;
    return out.count = 1;
  }
  const int cx = c + di, cy = c + dj * g.nx;
  const double vx = geo.cap_x[k], vy = geo.cap_y[k];
  if (dj == 0) {
    out.cell[0] = cx;
    out.volume[0] = vx;
    out.cell[1] = c;
    out.volume[1] = volume - vx;
    return out.count = 2;
  }
  if (di == 0) {
    out.cell[0] = cy;
    out.volume[0] = vy;
    out.cell[1] = c;
    out.volume[1] = volume - vy;
    return out.count = 2;
  }
  const double vxy = sphere_quadrant_volume(R, geo.a_x[k], geo.a_y[k]);
  out.cell[0] = cx + dj * g.nx;
  out.volume[0] = vxy;
  out.cell[1] = cx;
  out.volume[1] = vx - vxy;
  out.cell[2] = cy;
  out.volume[2] = vy - vxy;
  out.cell[3] = c;
  out.volume[3] = volume - vx - vy + vxy;
  return out.count = 4;
}

void add_particle_volume(const GasGrid& g, double x, double y, double R,
                         std::vector<double>& solid_volume) {
  VolumeShares shares;
  particle_volume_shares(g, x, y, R, shares);
  for (int k = 0; k < shares.count; ++k) solid_volume[shares.cell[k]] += shares.volume[k];
}

void porosity_from_solid(const GasGrid& g, const std::vector<double>& solid_volume,
                         std::vector<double>& eps) {
  eps.resize(solid_volume.size());
  const double inv_dv = 1.0 / g.cell_volume();
  for (std::size_t c = 0; c < solid_volume.size(); ++c) eps[c] = 1.0 - solid_volume[c] * inv_dv;
}

}  // namespace fluidbed
