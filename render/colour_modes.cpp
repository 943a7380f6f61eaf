#include "render/colour_modes.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed::render {

ColourScale colour_scale(ColourBy c, const Snapshot& s, double range_min, double range_max,
                         int height_bands) {
  ColourScale scale;
  switch (c) {
    case ColourBy::speed: scale = {0.0, 1.5, 0, false, "speed (m/s)"}; break;
    case ColourBy::force: scale = {7e-5, 0.7, 0, true, "force (N)"}; break;
    case ColourBy::torque: scale = {3e-8, 3e-4, 0, true, "torque (N m)"}; break;
    case ColourBy::overlap: scale = {0.0, 0.01, 0, false, "overlap / radii sum (0.01: 1 %)"}; break;
    case ColourBy::height: {
      double top = 0.0;
      for (double y : s.initial_y) top = std::max(top, y);
      scale = {0.0, top > 0.0 ? top : std::max(s.height, 1e-3), std::max(height_bands, 1), false,
               "initial height (m)"};
      break;
    }
    case ColourBy::depth:
      scale = {0.0, s.thickness > 0.0 ? s.thickness : 1e-3, 0, false, "depth from the front (m)"};
      break;
    case ColourBy::fixed: scale = {0.0, 1.0, 0, false, ""}; break;
  }
  if (range_min < range_max) {
    scale.min = range_min;
    scale.max = range_max;
    scale.log = scale.log && range_min > 0.0;
  }
  if (scale.log) scale.title.insert(scale.title.size() - 1, ", log scale");
  return scale;
}

double particle_value(ColourBy c, const Snapshot& s, std::size_t i) {
  switch (c) {
    case ColourBy::speed: return s.speed(i);
    case ColourBy::force: return s.force(i);
    case ColourBy::torque: return s.torque_magnitude(i);
    case ColourBy::overlap: return i < s.overlap.size() ? s.overlap[i] : 0.0;
    case ColourBy::height: return i < s.initial_y.size() ? s.initial_y[i] : s.y[i];
    case ColourBy::depth: return i < s.z.size() ? s.z[i] : 0.5 * s.thickness;
    case ColourBy::fixed: return 0.0;
  }
  return 0.0;
}

double depth_shade(const Snapshot& s, std::size_t i) {
  if (i >= s.z.size()) return 1.0;
  const double span = s.thickness - 2.0 * s.radius[i];
  if (!(span > 0.0)) return 1.0;  // no room to be behind another sphere
  const double t = std::clamp((s.z[i] - s.radius[i]) / span, 0.0, 1.0);
  return 1.0 - (1.0 - kBackShade) * t;
}

double scale_position(const ColourScale& scale, double value) {
  double t = scale.log ? (value > scale.min ? std::log(value / scale.min) : 0.0) /
                             std::log(scale.max / scale.min)
                       : (value - scale.min) / (scale.max - scale.min);
  if (!(t > 0.0)) t = 0.0;
  if (t > 1.0) t = 1.0;
  if (scale.bands > 0) {
    const double n = scale.bands;
    t = (std::min(std::floor(t * n), n - 1.0) + 0.5) / n;
  }
  return t;
}

double scale_value(const ColourScale& scale, double t) {
  return scale.log ? scale.min * std::pow(scale.max / scale.min, t)
                   : scale.min + t * (scale.max - scale.min);
}

}  // namespace fluidbed::render
