#include "render/picking.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed::render {

namespace {

bool within(const Rect& r, double x, double y) {
  return x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1;
}

}  // namespace

int bed_at(const FrameLayout& l, double fx, double fy) {
  for (std::size_t k = 0; k < l.beds.size(); ++k)
    if (within(l.beds[k].clip, fx, fy)) return static_cast<int>(k);
  return -1;
}

bool frame_to_world(const FrameLayout& l, double fx, double fy, double& x, double& y) {
  for (std::size_t k = 0; k < l.beds.size(); ++k) {
    const BedView& b = l.beds[k];
    if (!within(b.inside, fx, fy) || !within(b.clip, fx, fy)) continue;
    x = (fx - b.inside.x0) / b.scale;
    y = (b.inside.y1 - fy) / b.scale;
    return true;
  }
  return false;
}

void world_to_frame(const FrameLayout& l, double x, double y, double& fx, double& fy) {
  const BedView& b = l.beds.front();
  fx = b.px(x);
  fy = b.py(y);
}

std::optional<std::size_t> pick_particle(const Snapshot& s, const FrameLayout& l, double fx,
                                         double fy, double min_pixels) {
  for (const BedView& b : l.beds) {
    // Particles may stick out of a panel by a radius; allow that much around it.
    const double x = (fx - b.inside.x0) / b.scale, y = (b.inside.y1 - fy) / b.scale;
    const double slack = 0.5 * min_pixels / b.scale;
    // In a thick bed the front-most sphere under the point is the one drawn there (the renderer
    // draws back to front); among equals, and in a monolayer, the nearest centre.
    const bool depth = !s.z.empty() && s.z.size() == s.particles();
    std::optional<std::size_t> best;
    double best_d2 = 0.0;
    for (std::size_t i = 0; i < s.particles(); ++i) {
      const double r = std::max(s.radius[i], slack);
      const double dx = s.x[i] - x, dy = s.y[i] - y;
      const double d2 = dx * dx + dy * dy;
      if (d2 > r * r) continue;
      bool take = !best;
      if (best && depth && s.z[i] != s.z[*best])
        take = s.z[i] < s.z[*best];
      else if (best)
        take = d2 < best_d2;
      if (take) {
        best = i;
        best_d2 = d2;
      }
    }
    const double margin = best ? s.radius[*best] * b.scale : 0.0;
    const Rect reach{
        b.inside.x0 - static_cast<float>(margin), b.inside.y0 - static_cast<float>(margin),
        b.inside.x1 + static_cast<float>(margin), b.inside.y1 + static_cast<float>(margin)};
    if (best && within(reach, fx, fy) && (!b.zoomed || within(b.clip, fx, fy))) return best;
  }
  return std::nullopt;
}

ParticleContacts contacts_of(const Snapshot& s, std::size_t i) {
  ParticleContacts c;
  if (i >= s.particles()) return c;
  // In a thick bed spheres that cover each other on the picture may lie apart in depth, and the
  // front and back walls are walls like the others; a monolayer's spheres span the slab.
  const bool depth = !s.z.empty() && s.z.size() == s.particles();
  const double xi = s.x[i], yi = s.y[i], ri = s.radius[i];
  for (std::size_t j = 0; j < s.particles(); ++j) {
    if (j == i) continue;
    const double reach = ri + s.radius[j];
    const double dx = s.x[j] - xi, dy = s.y[j] - yi, dz = depth ? s.z[j] - s.z[i] : 0.0;
    if (std::fabs(dx) >= reach || std::fabs(dy) >= reach || std::fabs(dz) >= reach) continue;
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (d < reach) {
      c.particles.push_back(j);
      c.max_overlap = std::max(c.max_overlap, 1.0 - d / reach);
    }
  }
  c.walls = (xi - ri < 0.0 ? 1 : 0) + (xi + ri > s.width ? 1 : 0) + (yi - ri < 0.0 ? 1 : 0) +
            (s.top_wall && yi + ri > s.height ? 1 : 0);
  if (depth) c.walls += (s.z[i] - ri < 0.0 ? 1 : 0) + (s.z[i] + ri > s.thickness ? 1 : 0);
  return c;
}

}  // namespace fluidbed::render
