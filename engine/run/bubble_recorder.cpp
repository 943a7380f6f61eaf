#include "run/bubble_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/steps.hpp"

namespace fluidbed {

BubbleSettings bubble_settings_for(const Settings& s) {
  const BubbleSection& b = s.bubbles;
  BubbleSettings o = default_bubble_settings(s.particles.diameter);
  o.threshold = b.threshold;
  if (b.min_diameter > 0.0) o.min_diameter = b.min_diameter;
  if (b.cell_size > 0.0) o.cell_size = b.cell_size;
  if (b.window > 0.0) o.window = b.window;
  o.interval = b.interval;
  o.slug_fraction = b.slug_fraction;
  o.min_track_frames = b.min_track_frames;
  o.eruption_gap = b.eruption_gap;
  o.slugging_min_fraction = b.slugging_min_fraction;
  o.spouting_min_fraction = b.spouting_min_fraction;
  o.bed_min_fraction = b.bed_min_fraction;
  return o;
}

BedGeometry bubble_geometry_for(const Settings& s) {
  BedGeometry g;
  g.width = s.domain.width;
  g.height = s.domain.height;
  g.thickness = s.domain.thickness;
  g.particle_diameter = s.particles.diameter;
  g.gravity = s.physics.gravity;
  const bool jet = s.gas.enabled && s.inlet.kind == InletKind::Jet;
  g.jets = jet_slots(s.domain.width, jet ? s.inlet.jets : 0, s.inlet.jet_width);
  return g;
}

void add_bubble_fields(BubbleAnalysis& analysis, const Simulation& sim, Snapshot& s) {
  analysis.analyse(sim.time(), sim.dem().particles());
  add_bubble_fields(analysis, s);
}

void add_bubble_fields(const BubbleAnalysis& analysis, Snapshot& s) {
  const BubbleFrame& f = analysis.frame();
  const VoidFractionField& v = analysis.void_fraction();
  s.void_nx = v.grid.nx;
  s.void_ny = v.grid.ny;
  s.void_dx = v.grid.dx;
  s.void_dy = v.grid.dy;
  s.void_fraction.assign(v.eps.begin(), v.eps.end());
  s.bubble_edges.clear();
  outline_edges(f, v.grid, s.bubble_edges);
}

BubbleRecorder::BubbleRecorder(const Simulation& sim)
    : analysis_(bubble_settings_for(sim.settings()), bubble_geometry_for(sim.settings())),
      kind_(kinds_by_initial_height(sim.initial_heights())),
      width_(sim.settings().domain.width),
      height_(sim.settings().domain.height) {
  const Settings& s = sim.settings();
  every_ = std::max<std::int64_t>(1, steps_for(s.bubbles.interval, s.time.dt));
}

void BubbleRecorder::after_step(const Simulation& sim) {
  if (sim.steps() % every_ == 0) analyse(sim);
}

void BubbleRecorder::analyse(const Simulation& sim) {
  const double t = sim.time();
  const Particles& p = sim.dem().particles();
  const BubbleFrame& f = analysis_.analyse(t, p);
  analysis_.append_rows(rows_);
  bubbles_now_ = static_cast<int>(
      std::count_if(f.regions.begin(), f.regions.end(), [](const Bubble& b) { return !b.touches_jet; }));
  regime_now_ = analysis_.regime(t - kRegimeWindow, t);
  // kind_ is by id (the heights at the start); the particles are in the solver's order.
  std::vector<std::uint8_t> kind = kind_;
  sim.dem().to_places(kind);
  const LaceyResult m = lacey_index(p, kind, width_, height_);
  mixing_.push_back({t, m.ok ? m.index : std::numeric_limits<double>::quiet_NaN()});
}

nlohmann::json BubbleRecorder::bubbles_summary(double averaging_start) const {
  nlohmann::json j = to_json(analysis_.statistics(averaging_start));
  j["interval_s"] = analysis_.settings().interval;
  j["threshold"] = analysis_.settings().threshold;
  j["min_diameter_m"] = analysis_.settings().min_diameter;
  return j;
}

// Saved as their bytes (core/binary_io.hpp).
static_assert(std::is_trivially_copyable_v<BubbleRow> && std::is_trivially_copyable_v<MixingSample>);

nlohmann::json BubbleRecorder::mixing_summary() const {
  nlohmann::json j;
  const auto last = std::find_if(mixing_.rbegin(), mixing_.rend(),
                                 [](const MixingSample& m) { return std::isfinite(m.index); });
  j["lacey_index_final"] = last != mixing_.rend() ? nlohmann::json(last->index) : nlohmann::json(nullptr);
  j["samples"] = mixing_.size();
  return j;
}

}  // namespace fluidbed
