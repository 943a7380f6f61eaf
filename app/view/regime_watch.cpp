#include "view/regime_watch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/steps.hpp"
#include "run/bubble_recorder.hpp"

namespace fluidbed::app {

const Bubble* BubbleView::region_at(double x, double y) const {
  if (grid.nx <= 0 || grid.ny <= 0 || !(x >= 0.0) || !(y >= 0.0)) return nullptr;
  const auto i = static_cast<int>(std::floor(x / grid.dx));
  const auto j = static_cast<int>(std::floor(y / grid.dy));
  if (i >= grid.nx || j >= grid.ny) return nullptr;
  const std::size_t c = static_cast<std::size_t>(grid.index(i, j));
  if (c >= label.size() || label[c] < 0 || static_cast<std::size_t>(label[c]) >= regions.size())
    return nullptr;
  return &regions[static_cast<std::size_t>(label[c])];
}

std::string regime_words(const BubbleView& v) {
  std::string w = v.shown == Regime::fixed      ? "fixed bed"
                  : v.shown == Regime::expanded ? "expanded bed"
                                                : to_string(v.shown);
  if (v.window_s < 0.5 * RegimeWatch::kWindow) w += "?";  // too few frames to be sure
  return w;
}

Regime RegimeLabel::update(double t, Regime raw) {
  if (!started_) {  // the first frame shows what it sees
    started_ = true;
    shown_ = candidate_ = raw;
    since_ = t;
    return shown_;
  }
  if (raw != candidate_) {
    candidate_ = raw;
    since_ = t;
  }
  if (candidate_ != shown_ && t - since_ >= kHold - 1e-9) shown_ = candidate_;
  return shown_;
}

RiseShown rise_shown(const Bubble& b, int frames_seen, int min_track_frames) {
  RiseShown r;
  if (b.touches_jet) {
    r.words = "the jet's cavity: no rise velocity";
  } else if (!b.has_velocity) {
    r.words = "rise velocity: not measured in this frame (just formed or merged)";
  } else if (frames_seen < min_track_frames) {
    r.words = "rise velocity: not yet (tracked over " + std::to_string(frames_seen) + " of the " +
              std::to_string(min_track_frames) + " frames it needs)";
  } else if (!(b.vy > 0.0)) {
    r.words = "not rising: its centre moves down (a void closing, or its roof falling in)";
  } else {
    r.shown = true;
    r.vy = b.vy;
  }
  return r;
}

std::string mean_rise_words(const BubbleStatistics& w) {
  if (w.velocity_samples <= 0 || !std::isfinite(w.mean_rise_velocity_m_s)) return "";
  if (w.mean_rise_velocity_m_s > 0.0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "rising at %.2f m/s", w.mean_rise_velocity_m_s);
    return buf;
  }
  return "the voids did not rise on average (collapsing, not bubbling)";
}

RegimeWatch::RegimeWatch(const Settings& scene, const Simulation& sim)
    : settings_(bubble_settings_for(scene)), geometry_(bubble_geometry_for(scene)) {
  every_ = std::max<std::int64_t>(1, steps_for(settings_.interval, scene.time.dt));
  analyse(sim);
}

void RegimeWatch::restart(const Simulation& sim) {
  analysis_.reset();
  label_.restart();
  analyse(sim);
}

bool RegimeWatch::after_step(const Simulation& sim) {
  if (sim.steps() % every_ != 0) return false;
  analyse(sim);
  return true;
}

void RegimeWatch::analyse(const Simulation& sim) {
  const double t = sim.time();
  if (!analysis_) {
    analysis_ = std::make_unique<BubbleAnalysis>(settings_, geometry_);
    started_ = t;
  }
  const BubbleFrame& f = analysis_->analyse(t, sim.dem().particles());
  auto v = std::make_shared<BubbleView>();
  v->t = t;
  const double from = std::max(started_, t - kWindow);
  v->window = analysis_->history().summarize(from, t, settings_, geometry_.gravity);
  // Later windows start at `from` or after: what is older goes (memory flat however long the
  // class runs; the frames before it are read again by no summary).
  analysis_->forget_before(from);
  v->window_s = t - from;
  v->shown = label_.update(t, v->window.regime);
  v->gravity = geometry_.gravity;
  const VoidFractionField& field = analysis_->void_fraction();
  v->grid = field.grid;
  v->label = f.label;
  v->regions = f.regions;
  v->min_track_frames = settings_.min_track_frames;
  const std::vector<int>& seen = analysis_->history().id_frames;
  v->frames_seen.reserve(f.regions.size());
  for (const Bubble& b : f.regions)
    v->frames_seen.push_back(b.id >= 0 && static_cast<std::size_t>(b.id) < seen.size()
                                 ? seen[static_cast<std::size_t>(b.id)]
                                 : 0);
  outline_edges(f, field.grid, v->edges);
  v->void_fraction.assign(field.eps.begin(), field.eps.end());
  view_ = std::move(v);
}

}  // namespace fluidbed::app
