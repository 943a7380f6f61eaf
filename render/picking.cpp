#include "render/picking.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed::render {

void ViewTransform::clamp(double max_zoom) {
  zoom = std::clamp(std::isfinite(zoom) ? zoom : 1.0, 1.0, max_zoom);
  const double half = 0.5 / zoom;
  centre_x = std::clamp(std::isfinite(centre_x) ? centre_x : 0.5, half, 1.0 - half);
  centre_y = std::clamp(std::isfinite(centre_y) ? centre_y : 0.5, half, 1.0 - half);
}

void ViewTransform::zoom_about(double factor, double u, double v) {
  // The frame fraction under (u, v) before and after must be the same point.
  const double fx = centre_x + (u - 0.5) / zoom;
  const double fy = centre_y + (v - 0.5) / zoom;
  zoom *= factor;
  clamp();
  centre_x = fx - (u - 0.5) / zoom;
  centre_y = fy - (v - 0.5) / zoom;
  clamp();
}

void ViewTransform::pan_by(double du, double dv) {
  centre_x -= du / zoom;
  centre_y -= dv / zoom;
  clamp();
}

Rect visible_rect(const ViewTransform& t, int fw, int fh) {
  const double w = fw / t.zoom, h = fh / t.zoom;
  const double x0 = t.centre_x * fw - 0.5 * w, y0 = t.centre_y * fh - 0.5 * h;
  return {static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(x0 + w),
          static_cast<float>(y0 + h)};
}

void window_to_frame(const ViewTransform& t, const Rect& area, int fw, int fh, double wx, double wy,
                     double& fx, double& fy) {
  const Rect v = visible_rect(t, fw, fh);
  fx = v.x0 + (wx - area.x0) * v.width() / area.width();
  fy = v.y0 + (wy - area.y0) * v.height() / area.height();
}

void frame_to_window(const ViewTransform& t, const Rect& area, int fw, int fh, double fx, double fy,
                     double& wx, double& wy) {
  const Rect v = visible_rect(t, fw, fh);
  wx = area.x0 + (fx - v.x0) * area.width() / v.width();
  wy = area.y0 + (fy - v.y0) * area.height() / v.height();
}

bool frame_to_world(const FrameLayout& l, double fx, double fy, double& x, double& y) {
  for (std::size_t k = 0; k < l.beds.size(); ++k) {
    const BedView& b = l.beds[k];
    if (fx < b.inside.x0 || fx > b.inside.x1 || fy < b.inside.y0 || fy > b.inside.y1) continue;
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
    std::optional<std::size_t> best;
    double best_d2 = 0.0;
    for (std::size_t i = 0; i < s.particles(); ++i) {
      const double r = std::max(s.radius[i], slack);
      const double dx = s.x[i] - x, dy = s.y[i] - y;
      const double d2 = dx * dx + dy * dy;
      if (d2 <= r * r && (!best || d2 < best_d2)) {
        best = i;
        best_d2 = d2;
      }
    }
    const double margin = best ? s.radius[*best] * b.scale : 0.0;
    if (best && fx >= b.inside.x0 - margin && fx <= b.inside.x1 + margin &&
        fy >= b.inside.y0 - margin && fy <= b.inside.y1 + margin)
      return best;
  }
  return std::nullopt;
}

ParticleContacts contacts_of(const Snapshot& s, std::size_t i) {
  ParticleContacts c;
  if (i >= s.particles()) return c;
  const double xi = s.x[i], yi = s.y[i], ri = s.radius[i];
  for (std::size_t j = 0; j < s.particles(); ++j) {
    if (j == i) continue;
    const double reach = ri + s.radius[j];
    const double dx = s.x[j] - xi, dy = s.y[j] - yi;
    if (std::fabs(dx) >= reach || std::fabs(dy) >= reach) continue;
    const double d = std::sqrt(dx * dx + dy * dy);
    if (d < reach) {
      c.particles.push_back(j);
      c.max_overlap = std::max(c.max_overlap, 1.0 - d / reach);
    }
  }
  c.walls = (xi - ri < 0.0 ? 1 : 0) + (xi + ri > s.width ? 1 : 0) + (yi - ri < 0.0 ? 1 : 0) +
            (s.top_wall && yi + ri > s.height ? 1 : 0);
  return c;
}

}  // namespace fluidbed::render
