#include "analysis/mechanical_energy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace fluidbed {

MechanicalEnergy mechanical_energy(const Particles& p, const std::vector<Wall>& walls, double kn,
                                   double gravity) {
  MechanicalEnergy e;
  const std::size_t n = p.size();
  if (n == 0) return e;
  const bool depth = p.has_depth();  // a thick slab: z, its velocity and the spin about x, y
  double rmax = 0.0, x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    const double inertia = 1.0 / p.inv_inertia[i];
    e.kinetic += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i]) +
                 0.5 * inertia * p.w[i] * p.w[i];
    if (depth)
      e.kinetic += 0.5 * p.mass[i] * p.vz[i] * p.vz[i] +
                   0.5 * inertia * (p.wx[i] * p.wx[i] + p.wy[i] * p.wy[i]);
    e.potential += p.mass[i] * gravity * p.y[i];
    rmax = std::max(rmax, p.radius[i]);
    x0 = std::min(x0, p.x[i]);
    x1 = std::max(x1, p.x[i]);
    y0 = std::min(y0, p.y[i]);
    y1 = std::max(y1, p.y[i]);
  }
  if (!std::isfinite(e.kinetic + e.potential + x0 + x1 + y0 + y1)) {
    e.elastic = std::numeric_limits<double>::quiet_NaN();
    return e;
  }
  // Pairs through a grid of cells at least one largest diameter wide: a pair in contact lies in
  // the same or neighbouring cells. Cells are widened when the particles spread far (a blown-up
  // run) so that the grid never holds more than about 4 cells per particle.
  const double span_x = x1 - x0, span_y = y1 - y0;
  double cell = std::max(2.0 * rmax, 1e-12);
  const double max_cells = 4.0 * static_cast<double>(n) + 16.0;
  while ((span_x / cell + 1.0) * (span_y / cell + 1.0) > max_cells) cell *= 2.0;
  const auto nx = static_cast<std::int64_t>(span_x / cell) + 1;
  const auto ny = static_cast<std::int64_t>(span_y / cell) + 1;
  std::vector<std::int64_t> cell_of(n), start(static_cast<std::size_t>(nx * ny + 1), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto cx = std::min<std::int64_t>(static_cast<std::int64_t>((p.x[i] - x0) / cell), nx - 1);
    const auto cy = std::min<std::int64_t>(static_cast<std::int64_t>((p.y[i] - y0) / cell), ny - 1);
    cell_of[i] = cy * nx + cx;
    ++start[static_cast<std::size_t>(cell_of[i] + 1)];
  }
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<std::size_t> order(n);
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    order[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of[i])]++)] = i;

  double pairs = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t cx = cell_of[i] % nx, cy = cell_of[i] / nx;
    for (std::int64_t gy = std::max<std::int64_t>(cy - 1, 0); gy <= std::min(cy + 1, ny - 1); ++gy)
      for (std::int64_t gx = std::max<std::int64_t>(cx - 1, 0); gx <= std::min(cx + 1, nx - 1); ++gx) {
        const auto c = static_cast<std::size_t>(gy * nx + gx);
        for (std::int64_t q = start[c]; q < start[c + 1]; ++q) {
          const std::size_t j = order[static_cast<std::size_t>(q)];
          if (j <= i) continue;
          const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i];
          const double R = p.radius[i] + p.radius[j];
          const double dz = depth ? p.z[j] - p.z[i] : 0.0;
          const double d2 = dx * dx + dy * dy + dz * dz;
          if (d2 >= R * R) continue;
          const double delta = R - std::sqrt(d2);
          pairs += 0.5 * kn * delta * delta;
        }
      }
  }
  double wall = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (const Wall& w : walls) {
      const double d = w.nx * p.x[i] + w.ny * p.y[i] + (depth ? w.nz * p.z[i] : 0.0) - w.offset;
      if (d >= p.radius[i]) continue;
      const double delta = p.radius[i] - d;
      wall += 0.5 * kn * delta * delta;
    }
  e.elastic = pairs + wall;
  return e;
}

}  // namespace fluidbed
