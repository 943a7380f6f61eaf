// Bubble statistics over a window, the regime rule and the rows of bubbles.csv
// (analysis/bubble_statistics.hpp says what each means).
#include "analysis/bubble_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace fluidbed {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

// ---------------------------------------------------------------------------------------------
// Statistics

Regime classify_regime(const BubbleStatistics& st, const BubbleSettings& s) {
  if (st.frames == 0) return Regime::fixed;
  if (st.spouting_fraction >= s.spouting_min_fraction) return Regime::spouting;
  if (st.slugging_fraction >= s.slugging_min_fraction) return Regime::slugging;
  if (st.formed == 0 && st.slugging_fraction == 0.0)
    return st.bed_rise_m >= s.expanded_rise && st.median_particle_speed_m_s >= s.expanded_speed
               ? Regime::expanded
               : Regime::fixed;
  return Regime::bubbling;
}

void BubbleHistory::add(const BubbleFrame& frame, double dt) {
  Frame f;
  f.t = frame.t;
  f.dt = dt;
  f.spout = frame.spout;
  f.median_speed = frame.median_speed;
  double sum = 0.0;
  int columns = 0;
  for (double y : frame.surface) {
    if (y > 0.0) {
      sum += y;
      ++columns;
    }
  }
  f.surface = columns > 0 ? sum / columns : 0.0;
  if (reference_surface < 0.0) reference_surface = f.surface;
  const auto sample = [&](const Bubble& b, bool ended) {
    Sample q;
    q.t = frame.t;
    q.id = b.id;
    q.d_eq = b.d_eq;
    q.vx = b.vx;
    q.vy = b.vy;
    q.has_velocity = b.has_velocity;
    q.from_jet = b.from_jet;
    q.merged_id = b.merged_id;
    q.ended = ended;
    q.event = b.event;
    samples.push_back(q);
  };
  for (const Bubble& b : frame.regions) {
    if (b.touches_jet) {
      f.jet_cavity = true;
      continue;
    }
    f.slug = f.slug || b.slug;
    sample(b, false);
    if (b.id >= static_cast<int>(id_frames.size()))
      id_frames.resize(static_cast<std::size_t>(b.id) + 1, 0);
    ++id_frames[static_cast<std::size_t>(b.id)];
  }
  for (const Bubble& b : frame.ended) sample(b, true);
  frames.push_back(f);
}

void BubbleHistory::forget_before(double t) {
  // The last frame at or before t stays: summarize() starts the samples after the first frame.
  const auto after = std::upper_bound(frames.begin(), frames.end(), t,
                                      [](double u, const Frame& f) { return u < f.t; });
  if (after != frames.begin()) {
    const auto keep_from = std::prev(after);
    if (keep_from - frames.begin() >= frames.end() - keep_from)
      frames.erase(frames.begin(), keep_from);
  }
  const auto later = std::upper_bound(samples.begin(), samples.end(), t,
                                      [](double u, const Sample& q) { return u < q.t; });
  if (later - samples.begin() >= samples.end() - later) samples.erase(samples.begin(), later);
}

BubbleStatistics BubbleHistory::summarize(double t_from, double t_to, const BubbleSettings& s,
                                          double gravity) const {
  BubbleStatistics st;
  st.window_start = t_from;
  int slug_frames = 0, spout_frames = 0, jet_frames = 0;
  double sum_surface = 0.0, sum_speed = 0.0;
  for (const Frame& f : frames) {
    if (!(f.dt > 0.0) || !(f.t > t_from) || f.t > t_to) continue;
    ++st.frames;
    st.window_end = f.t;
    st.duration += f.dt;
    sum_surface += f.surface;
    sum_speed += f.median_speed;
    slug_frames += f.slug ? 1 : 0;
    spout_frames += f.spout ? 1 : 0;
    jet_frames += f.jet_cavity ? 1 : 0;
  }
  // The samples of the window: those of frames after the first (a first frame has no interval
  // before it), found by bisection in time.
  const double first = frames.empty() ? 0.0 : frames.front().t;
  const double lo = std::max(t_from, first);
  const auto later = [](double t, const Sample& q) { return t < q.t; };
  const auto begin = std::upper_bound(samples.begin(), samples.end(), lo, later);
  const auto end = std::upper_bound(samples.begin(), samples.end(), t_to, later);
  const auto frames_of = [&](int id) {
    return id >= 0 && id < static_cast<int>(id_frames.size())
               ? id_frames[static_cast<std::size_t>(id)]
               : 0;
  };
  double sum_d = 0.0, sum_vx = 0.0, sum_vy = 0.0, sum_ref = 0.0;
  std::vector<double> eruptions;  // s
  for (auto it = begin; it != end; ++it) {
    const Sample& q = *it;
    if (frames_of(q.id) < s.min_track_frames) {
      if (q.event == BubbleEvent::formed) ++st.flicker_ids;
      continue;
    }
    switch (q.event) {
      case BubbleEvent::formed:
        ++st.formed;
        if (q.from_jet) ++st.formed_at_jet;
        break;
      case BubbleEvent::coalesced:  // two lasting bubbles, not a flicker absorbed
        if (frames_of(q.merged_id) >= s.min_track_frames) ++st.coalesced;
        break;
      case BubbleEvent::split:
        ++st.split;
        break;
      case BubbleEvent::erupted:
        ++st.erupted;
        eruptions.push_back(q.t);
        break;
      case BubbleEvent::vanished:
        ++st.vanished;
        break;
      case BubbleEvent::none:
        break;
    }
    if (q.ended) continue;
    ++st.bubble_frames;
    sum_d += q.d_eq;
    if (q.has_velocity) {
      ++st.velocity_samples;
      sum_vx += q.vx;
      sum_vy += q.vy;
      sum_ref += 0.5 * std::sqrt(gravity * q.d_eq);
    }
  }
  for (std::size_t k = 0; k < eruptions.size(); ++k)
    if (k == 0 || eruptions[k] - eruptions[k - 1] > s.eruption_gap) ++st.eruption_bursts;

  const double T = st.duration;
  const auto rate = [T](int n) { return T > 0.0 ? n / T : 0.0; };
  st.formed_per_s = rate(st.formed);
  st.formed_at_jet_per_s = rate(st.formed_at_jet);
  st.eruptions_per_s = rate(st.eruption_bursts);
  st.erupted_bubbles_per_s = rate(st.erupted);
  st.coalescences_per_s = rate(st.coalesced);
  st.splits_per_s = rate(st.split);
  const double n = st.frames;
  st.mean_bubbles = st.frames > 0 ? st.bubble_frames / n : 0.0;
  st.mean_d_eq_m = st.bubble_frames > 0 ? sum_d / st.bubble_frames : kNaN;
  const double nv = st.velocity_samples;
  st.mean_rise_velocity_m_s = st.velocity_samples > 0 ? sum_vy / nv : kNaN;
  st.mean_vx_m_s = st.velocity_samples > 0 ? sum_vx / nv : kNaN;
  st.mean_rise_velocity_2d_ref_m_s = st.velocity_samples > 0 ? sum_ref / nv : kNaN;
  st.slugging_fraction = st.frames > 0 ? slug_frames / n : 0.0;
  st.spouting_fraction = st.frames > 0 ? spout_frames / n : 0.0;
  st.jet_cavity_fraction = st.frames > 0 ? jet_frames / n : 0.0;
  st.bed_rise_m = st.frames > 0 && reference_surface >= 0.0
                      ? sum_surface / n - reference_surface
                      : 0.0;
  st.median_particle_speed_m_s = st.frames > 0 ? sum_speed / n : 0.0;
  st.regime = classify_regime(st, s);
  return st;
}

nlohmann::json to_json(const BubbleStatistics& st) {
  const auto num = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  nlohmann::json j;
  j["window_start_s"] = st.window_start;
  j["window_end_s"] = st.window_end;
  j["duration_s"] = st.duration;
  j["frames"] = st.frames;
  j["formed"] = st.formed;
  j["formed_at_jet"] = st.formed_at_jet;
  j["coalesced"] = st.coalesced;
  j["split"] = st.split;
  j["erupted"] = st.erupted;
  j["vanished"] = st.vanished;
  j["formed_per_s"] = st.formed_per_s;
  j["formed_at_jet_per_s"] = st.formed_at_jet_per_s;
  j["eruption_bursts"] = st.eruption_bursts;
  j["eruptions_per_s"] = st.eruptions_per_s;
  j["erupted_bubbles_per_s"] = st.erupted_bubbles_per_s;
  j["coalescences_per_s"] = st.coalescences_per_s;
  j["splits_per_s"] = st.splits_per_s;
  j["mean_bubbles_per_frame"] = st.mean_bubbles;
  j["bubble_frames"] = st.bubble_frames;
  j["velocity_samples"] = st.velocity_samples;
  j["flicker_ids"] = st.flicker_ids;
  j["mean_d_eq_m"] = num(st.mean_d_eq_m);
  j["mean_rise_velocity_m_s"] = num(st.mean_rise_velocity_m_s);
  j["mean_vx_m_s"] = num(st.mean_vx_m_s);
  j["mean_rise_velocity_2d_ref_m_s"] = num(st.mean_rise_velocity_2d_ref_m_s);
  j["slugging_fraction"] = st.slugging_fraction;
  j["spouting_fraction"] = st.spouting_fraction;
  j["jet_cavity_fraction"] = st.jet_cavity_fraction;
  j["bed_rise_m"] = st.bed_rise_m;
  j["median_particle_speed_m_s"] = st.median_particle_speed_m_s;
  j["regime"] = to_string(st.regime);
  return j;
}

// ---------------------------------------------------------------------------------------------
// bubbles.csv

void append_rows(const BubbleFrame& frame, std::vector<BubbleRow>& rows) {
  const auto row = [&](const Bubble& b) {
    BubbleRow r;
    r.t = frame.t;
    r.id = b.id;
    r.x = b.x;
    r.y = b.y;
    r.d_eq = b.d_eq;
    r.area = b.area;
    r.width = b.width;
    r.height = b.height;
    r.vx = b.vx;
    r.vy = b.vy;
    r.has_velocity = b.has_velocity;
    r.event = b.event;
    rows.push_back(r);
  };
  for (const Bubble& b : frame.regions)
    if (!b.touches_jet) row(b);
  for (const Bubble& b : frame.ended) row(b);
}

void write_bubbles_csv_header(std::ostream& out) {
  out << "t,id,x,y,d_eq,area,width,height,vx,vy,event\n";
}

void write_bubbles_csv_rows(std::ostream& out, const std::vector<BubbleRow>& rows) {
  // printf formatting: the same text under any stream state or locale of the caller.
  char buf[320];
  for (const BubbleRow& r : rows) {
    int n = std::snprintf(buf, sizeof buf, "%.9g,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,", r.t, r.id, r.x,
                          r.y, r.d_eq, r.area, r.width, r.height);
    out.write(buf, n);
    if (r.has_velocity) {
      n = std::snprintf(buf, sizeof buf, "%.9g,%.9g,", r.vx, r.vy);
      out.write(buf, n);
    } else {
      out << ",,";
    }
    out << to_string(r.event) << '\n';
  }
}

}  // namespace fluidbed
