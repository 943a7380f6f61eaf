// The per-frame driver of the bubble analysis (analysis/bubbles.hpp): void fraction, detection,
// tracking and the history, in that order.
#include "analysis/bubbles.hpp"

#include <limits>
#include <stdexcept>

namespace fluidbed {

namespace {
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
