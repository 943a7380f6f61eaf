#pragma once
// The viewer's live Fig. 6: the mean pressure drop at each gas velocity the teacher holds,
// built as the class watches. A held velocity gives one point: after a settling time (the bed
// finds its new state) the pressure drop is averaged over a window of simulated time, as `sweep`
// averages each of its runs (eq 30). The point goes on the branch of the direction of the last
// change, measured from the last point taken (a slider dragged past its mark and back is one
// change): increasing (the bed starts packed, so until a point is taken the branch is the
// increasing one) or decreasing; a change against the branch's direction starts a new branch
// from the last point (the turning point belongs to both, as the sweep's top run does). U_mf is
// fitted to the last decreasing branch with the sweep's fit (analysis/umf_fit.hpp) and shown once
// that fit finds it inside the branch's range. No threads, no GL: the view session
// (view/session.hpp) owns one and feeds it the simulated time, the held velocity and dp.
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/umf_fit.hpp"

namespace fluidbed::app {

struct CurvePoint {
  double u = 0.0;        // m/s, the held superficial velocity
  double dp_mean = 0.0;  // Pa, over the averaging window
  double dp_std = 0.0;   // Pa, of the samples in it
  int samples = 0;       // dp samples averaged
  double t_from = 0.0;   // s, the window's start (simulated)
  double t_to = 0.0;     // s, its end
  double settle = 0.0;   // s, the settling time it waited
  bool shared = false;   // the previous branch's last point, where this branch turned
};

struct CurveBranch {
  bool increasing = true;
  std::vector<CurvePoint> points;  // in the order taken
};

// Where the current hold is.
enum class HoldPhase { settling, averaging, done };

// What the panel draws (a plain copy).
struct CurveState {
  std::vector<CurveBranch> branches;  // oldest first; never empty
  double settle = 0.0, window = 0.0;  // s
  double held_u = 0.0;                // m/s
  double held_since = 0.0;            // s, simulated time of the last change
  HoldPhase phase = HoldPhase::settling;
  double phase_left = 0.0;       // s of simulated time until the phase ends
  UmfFit umf;                    // the last decreasing branch's fit (ok: shown)
  double weight_per_area = 0.0;  // Pa, the bed's weight over the bed's cross-section
  std::uint64_t version = 0;     // changes whenever a point is added or the curve cleared
};

class LiveCurve {
 public:
  // Times in simulated seconds: `settle` >= 0, `window` > 0 (InputError otherwise). The hold
  // starts at t0 with velocity u0.
  LiveCurve(double settle, double window, double weight_per_area, double t0, double u0);

  // The held velocity changed at simulated time t (to u, m/s). An equal velocity changes nothing.
  void velocity(double t, double u);
  // The bed changed in another way (contact law): the current velocity settles again.
  void restart_hold(double t);
  // New settling time or window (InputError for bad values): the current hold starts its
  // averaging again from t (samples before it came with the old times).
  void set_times(double t, double settle, double window);
  // A pressure-drop sample at simulated time t (every output interval). True when it completed a
  // point.
  bool sample(double t, double dp);
  // Back to nothing with another bed weight (Pa; new particles), from t at velocity u.
  void clear(double t, double u, double weight_per_area) {
    st_.weight_per_area = weight_per_area;
    clear(t, u);
  }
  // Back to nothing: the bed was reset to the packed bed at t with velocity u.
  void clear(double t, double u);

  const CurveState& state() const { return st_; }

 private:
  void update_phase(double t);
  void refit();
  void finish_hold(double t);
  bool take_point();
  const CurvePoint* last_point() const;

  CurveState st_;
  double avg_from_ = 0.0;  // s, the current hold's averaging window [avg_from_, avg_from_ + window]
  double sum_ = 0.0, sum_sq_ = 0.0;
  int n_ = 0;
  bool taken_ = false;    // the current hold gave its point
  double last_t_ = 0.0;   // s, the last sample's time
  double spacing_ = 0.0;  // s between the last two samples
};

// The points as CSV: one row per point taken (a turning point once, on the branch it was taken
// on): branch,direction,u_m_s,dp_mean_pa,dp_std_pa,samples,t_from_s,t_to_s,settle_s.
void write_curve_csv(std::ostream& out, const CurveState& c);
// The curve in one line: "live curve: 12 points (6 increasing, 6 decreasing); U_mf from the
// decreasing branch 2.05 m/s" (or why there is none).
std::string describe_curve(const CurveState& c);
// Where the hold is, in words: "settling at 2.20 m/s: 0.32 s left", "averaging ...", "point
// taken at 2.20 m/s".
std::string describe_phase(const CurveState& c);

}  // namespace fluidbed::app
