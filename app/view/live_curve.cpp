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
  st_.umf = UmfFit{};
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
  const bool up = u > st_.held_u;
  CurveBranch& cur = st_.branches.back();
  const bool own_points = std::any_of(cur.points.begin(), cur.points.end(),
                                      [](const CurvePoint& p) { return !p.shared; });
  if (cur.increasing != up) {
    if (!own_points && st_.branches.size() > 1) {
      // A turn and back before any point was taken: the previous branch goes on.
      st_.branches.pop_back();
    } else if (!own_points) {
      cur.increasing = up;  // nothing on it yet: it takes the direction
    } else {
      CurveBranch next;
      next.increasing = up;
      CurvePoint turn = cur.points.back();
      turn.shared = true;
      next.points.push_back(turn);
      st_.branches.push_back(std::move(next));
    }
    ++st_.version;
    refit();
  }
  st_.held_u = u;
  restart_hold(t);
}

bool LiveCurve::sample(double t, double dp) {
  // Half the spacing of the samples: the window ends at the sample nearest its end (samples come
  // at the steps nearest their times, a step to either side).
  const double half = last_t_ < t ? 0.5 * (t - last_t_) : 0.0;
  last_t_ = t;
  if (taken_) return false;  // one point per hold: nothing more until a change
  const double to = avg_from_ + st_.window;
  bool added = false;
  if (t > avg_from_ + kSlack && t <= to + half && std::isfinite(dp)) {
    sum_ += dp;
    sum_sq_ += dp * dp;
    ++n_;
  }
  if (t >= to - half - kSlack && n_ > 0) {
    CurvePoint p;
    p.u = st_.held_u;
    p.samples = n_;
    p.dp_mean = sum_ / n_;
    p.dp_std = std::sqrt(std::max(0.0, sum_sq_ / n_ - p.dp_mean * p.dp_mean));
    p.t_from = avg_from_;
    p.t_to = to;
    p.settle = avg_from_ - st_.held_since;
    st_.branches.back().points.push_back(p);
    ++st_.version;
    refit();
    added = true;
    taken_ = true;
  }
  update_phase(t);
  return added;
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
