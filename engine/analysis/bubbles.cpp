// The per-frame driver of the bubble analysis (analysis/bubbles.hpp): void fraction, detection,
// tracking and the history, in that order.
#include "analysis/bubbles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fluidbed {

namespace {
// The median of the particles' speeds (in three dimensions in a thick bed); `scratch` is reused.
double median_speed(const Particles& p, std::vector<double>& scratch) {
  const std::size_t n = p.size();
  if (n == 0) return 0.0;
  scratch.resize(n);
  const bool depth = p.vz.size() == n;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = depth ? p.vz[i] : 0.0;
    scratch[i] = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + w * w);
  }
  const auto mid = scratch.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(scratch.begin(), mid, scratch.end());
  return *mid;
}

const BubbleSettings& checked(const BubbleSettings& s, const BedGeometry& g) {
  validate(s, g);
  return s;
}
}  // namespace

BubbleAnalysis::BubbleAnalysis(const BubbleSettings& s, const BedGeometry& g)
    : s_(checked(s, g)),
      g_(g),
      field_(make_void_fraction_field(
          make_fine_grid(g.width, g.height, g.thickness, s.cell_size, g.particle_diameter),
          s.window)),
      detector_(s_, g_),
      tracker_(s_, field_.grid) {}

const BubbleFrame& BubbleAnalysis::analyse(double t, const Particles& p) {
  if (started_ && !(t > last_t_))
    throw std::invalid_argument("BubbleAnalysis::analyse: time must increase");
  compute_void_fraction(p, field_);
  frame_.t = t;
  frame_.median_speed = median_speed(p, speeds_);
  detector_.detect(field_, frame_);
  tracker_.track(frame_);
  history_.add(frame_, started_ ? t - last_t_ : 0.0);
  last_t_ = t;
  started_ = true;
  return frame_;
}

BubbleStatistics BubbleAnalysis::statistics(double averaging_start) const {
  return history_.summarize(averaging_start, std::numeric_limits<double>::infinity(), s_,
                            g_.gravity);
}

Regime BubbleAnalysis::regime(double t_from, double t_to) const {
  return history_.summarize(t_from, t_to, s_, g_.gravity).regime;
}

}  // namespace fluidbed
