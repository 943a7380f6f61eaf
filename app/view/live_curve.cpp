#include "view/live_curve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.hpp"

namespace fluidbed::app {
namespace {

void check_times(double settle, double window) {
  if (!(settle >= 0.0) || !std::isfinite(settle))
    throw InputError("the settling time must be >= 0 s (got " + std::to_string(settle) + ")");
  if (!(window > 0.0) || !std::isfinite(window))
    throw InputError("the averaging window must be > 0 s (got " + std::to_string(window) + ")");
}

// Round-off on the window's start (samples and window ends are sums of time steps).
constexpr double kSlack = 1e-9;

}  // namespace

LiveCurve::LiveCurve(double settle, double window, double weight_per_area, double t0, double u0) {
  check_times(settle, window);
  st_.settle = settle;
  st_.window = window;
  st_.weight_per_area = weight_per_area;
  clear(t0, u0);
}

void LiveCurve::clear(double t, double u) {
  last_t_ = t;
  st_.branches.assign(1, CurveBranch{});  // the packed bed: the increasing branch
  st_.held_u = u;
  refit();
  ++st_.version;
  restart_hold(t);
}

void LiveCurve::restart_hold(double t) {
  st_.held_since = t;
  avg_from_ = t + st_.settle;
  sum_ = sum_sq_ = 0.0;
  n_ = 0;
  taken_ = false;
  update_phase(t);
}

void LiveCurve::set_times(double t, double settle, double window) {
  check_times(settle, window);
  st_.settle = settle;
  st_.window = window;
  // The hold keeps its start; samples already summed came under the old times.
  avg_from_ = std::max(st_.held_since + settle, t);
  sum_ = sum_sq_ = 0.0;
  n_ = 0;
  update_phase(t);
}

void LiveCurve::velocity(double t, double u) {
  if (u == st_.held_u) return;
  finish_hold(t);
  st_.held_u = u;
  // The direction: against the last point taken (a slider dragged past its mark and back is
  // still one change); before any point, the packed bed's increasing branch.
  const CurvePoint* last = last_point();
  if (last && u != last->u) {
    const bool up = u > last->u;
    CurveBranch& cur = st_.branches.back();
    const bool own_points = std::any_of(cur.points.begin(), cur.points.end(),
                                        [](const CurvePoint& p) { return !p.shared; });
    if (cur.increasing != up) {
      if (!own_points && st_.branches.size() > 1) {
        st_.branches.pop_back();  // a turn and back before a point: the previous branch goes on
      } else if (!own_points) {
        cur.increasing = up;
      } else {
        CurveBranch next;  // from the turning point, which belongs to both
        next.increasing = up;
        CurvePoint turn = cur.points.back();
        turn.shared = true;
        next.points.push_back(turn);
        st_.branches.push_back(std::move(next));
      }
      ++st_.version;
      refit();
    }
  }
  restart_hold(t);
}

const CurvePoint* LiveCurve::last_point() const {
  for (auto b = st_.branches.rbegin(); b != st_.branches.rend(); ++b)
    if (!b->points.empty()) return &b->points.back();
  return nullptr;
}

bool LiveCurve::sample(double t, double dp) {
  // Half the spacing of the samples: the window ends at the sample nearest its end (samples come
  // at the steps nearest their times, a step to either side).
  if (last_t_ < t) spacing_ = t - last_t_;
  last_t_ = t;
  if (taken_) return false;  // one point per hold: nothing more until a change
  const double half = 0.5 * spacing_;
  const double to = avg_from_ + st_.window;
  if (t > avg_from_ + kSlack && t <= to + half && std::isfinite(dp)) {
    sum_ += dp;
    sum_sq_ += dp * dp;
    ++n_;
  }
  const bool added = t >= to - half - kSlack && take_point();
  update_phase(t);
  return added;
}

void LiveCurve::finish_hold(double t) {
  // A change that comes within a sample and a half of the window's end (the samples' grid need
  // not meet it) completes the point with what was averaged.
  if (!taken_ && t >= avg_from_ + st_.window - 1.5 * spacing_ - kSlack) take_point();
}

bool LiveCurve::take_point() {
  if (n_ <= 0) return false;
  CurvePoint p;
  p.u = st_.held_u;
  p.samples = n_;
  p.dp_mean = sum_ / n_;
  p.dp_std = std::sqrt(std::max(0.0, sum_sq_ / n_ - p.dp_mean * p.dp_mean));
  p.t_from = avg_from_;
  p.t_to = avg_from_ + st_.window;
  p.settle = avg_from_ - st_.held_since;
  st_.branches.back().points.push_back(p);
  ++st_.version;
  refit();
  taken_ = true;
  return true;
}

void LiveCurve::update_phase(double t) {
  if (taken_) {
    st_.phase = HoldPhase::done;
    st_.phase_left = 0.0;
  } else if (t < avg_from_) {
    st_.phase = HoldPhase::settling;
    st_.phase_left = avg_from_ - t;
  } else {
    st_.phase = HoldPhase::averaging;
    st_.phase_left = std::max(0.0, avg_from_ + st_.window - t);
  }
}

void LiveCurve::refit() {
  st_.umf = UmfFit{};
  for (auto b = st_.branches.rbegin(); b != st_.branches.rend(); ++b) {
    if (b->increasing) continue;
    std::vector<double> u, dp;
    for (const CurvePoint& p : b->points) {
      u.push_back(p.u);
      dp.push_back(p.dp_mean);
    }
    UmfFit f = fit_umf(u, dp);
    const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
    if (f.ok && !(f.umf > *lo && f.umf < *hi)) {
      f.ok = false;
      f.why = "the fit's U_mf lies outside the branch's velocities";
    }
    st_.umf = f;
    return;
  }
  st_.umf.why = "no decreasing branch yet";
}

void write_curve_csv(std::ostream& out, const CurveState& c) {
  out << "branch,direction,u_m_s,dp_mean_pa,dp_std_pa,samples,t_from_s,t_to_s,settle_s\n";
  char line[256];
  for (std::size_t b = 0; b < c.branches.size(); ++b)
    for (const CurvePoint& p : c.branches[b].points) {
      if (p.shared) continue;
      std::snprintf(line, sizeof line, "%zu,%s,%.6g,%.6g,%.6g,%d,%.6g,%.6g,%.6g\n", b + 1,
                    c.branches[b].increasing ? "increasing" : "decreasing", p.u, p.dp_mean,
                    p.dp_std, p.samples, p.t_from, p.t_to, p.settle);
      out << line;
    }
}

std::string describe_curve(const CurveState& c) {
  int up = 0, down = 0;
  for (const CurveBranch& b : c.branches)
    for (const CurvePoint& p : b.points)
      if (!p.shared) ++(b.increasing ? up : down);
  char buf[160];
  std::snprintf(buf, sizeof buf, "live curve: %d points (%d increasing, %d decreasing); ",
                up + down, up, down);
  std::string s = buf;
  if (c.umf.ok) {
    std::snprintf(buf, sizeof buf, "U_mf from the decreasing branch %.3f m/s", c.umf.umf);
    return s + buf;
  }
  return s + "no U_mf yet (" + c.umf.why + ")";
}

std::string describe_phase(const CurveState& c) {
  char buf[128];
  switch (c.phase) {
    case HoldPhase::settling:
      std::snprintf(buf, sizeof buf, "settling at %.2f m/s: %.2f s left", c.held_u, c.phase_left);
      break;
    case HoldPhase::averaging:
      std::snprintf(buf, sizeof buf, "averaging dp at %.2f m/s: %.2f s left", c.held_u,
                    c.phase_left);
      break;
    case HoldPhase::done:
      std::snprintf(buf, sizeof buf, "point taken at %.2f m/s: change U for the next", c.held_u);
      break;
  }
  return buf;
}

}  // namespace fluidbed::app
