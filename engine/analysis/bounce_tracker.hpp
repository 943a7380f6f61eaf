#pragma once
// The drop test's measurements, taken step by step on particle 0 and the bottom wall (wall 0):
// the restitution of each bounce (rebound over impact speed, both extrapolated ballistically to
// the instant of touching, so the step's phase does not bias them) and the apex height after each
// bounce, measured as the gap between the sphere and the floor.
#include <cmath>
#include <vector>

#include "core/binary_io.hpp"
#include "dem/dem_solver.hpp"

namespace fluidbed {

class BounceTracker {
 public:
  BounceTracker(const DemSolver& dem, double gravity) : g_(gravity) {
    const Particles& p = dem.particles();
    const std::size_t i = dem.place_of(0);
    drop_height_ = p.y[i] - p.radius[i];
    record(dem);
  }

  // Call after every step.
  void observe(const DemSolver& dem) {
    // particle 0, bottom wall (wall 0 of its row)
    const auto row = static_cast<std::size_t>(dem.state().walls.walls) * dem.place_of(0);
    const bool touching = dem.state().walls.active[row] != 0;
    if (touching && !in_contact_) {
      in_contact_ = true;
      impact_speed_ = touch_speed(last_gap_, last_vy_);
      if (bounces_ > 0) apex_heights_.push_back(apex_);
    } else if (!touching && in_contact_) {
      in_contact_ = false;
      ++bounces_;
      record(dem);
      restitutions_.push_back(touch_speed(last_gap_, last_vy_) / impact_speed_);
      apex_ = last_gap_;
      return;
    }
    record(dem);
    if (!in_contact_ && bounces_ > 0) apex_ = std::max(apex_, last_gap_);
  }

  // Apex heights after each bounce so far (the current flight counts once it has turned down).
  std::vector<double> apex_heights() const {
    std::vector<double> a = apex_heights_;
    if (!in_contact_ && bounces_ > static_cast<int>(a.size()) && last_vy_ < 0.0) a.push_back(apex_);
    return a;
  }
  const std::vector<double>& restitutions() const { return restitutions_; }
  double drop_height() const { return drop_height_; }

  // Its state, for a run's checkpoint (run/checkpoint.hpp, core/binary_io.hpp).
  template <class Archive>
  void fields(Archive& a) {
    a.tag("FLBBNC02", "bounce tracker");
    a(g_, drop_height_, last_gap_, last_vy_, impact_speed_, apex_, in_contact_, bounces_,
      restitutions_, apex_heights_);
  }
  void save(BinarySink& out) const { out(*this); }
  void restore(BinarySource& in) { in(*this); }

 private:
  void record(const DemSolver& dem) {
    const Particles& p = dem.particles();
    const std::size_t i = dem.place_of(0);
    last_gap_ = p.y[i] - p.radius[i];
    last_vy_ = p.vy[i];
  }
  double touch_speed(double gap, double vy) const {
    return std::sqrt(vy * vy + 2.0 * g_ * std::max(gap, 0.0));
  }

  double g_;
  double drop_height_ = 0.0;
  double last_gap_ = 0.0, last_vy_ = 0.0;
  bool in_contact_ = false;
  int bounces_ = 0;
  double impact_speed_ = 0.0;
  double apex_ = 0.0;
  std::vector<double> restitutions_;
  std::vector<double> apex_heights_;
};

}  // namespace fluidbed
