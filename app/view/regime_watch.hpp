#pragma once
// The viewer's bubble analysis: the state analysed every [bubbles] interval of simulated time (the
// cadence `run --bubbles` uses, so tracking and the regime rule see the frames they were made
// for), the regime of the last second in words, the outlines for the picture, and each bubble's
// cells for the pointer. Runs between steps in the view session (view/session.hpp: the window's
// engine thread, or the headless viewer); readers get an immutable view.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "analysis/bubbles.hpp"
#include "scene/settings.hpp"
#include "sim/simulation.hpp"

namespace fluidbed::app {

// One analysed frame and the statistics of the trailing window, as the panel and the picture use
// them (a plain copy, shared read-only).
struct BubbleView {
  double t = 0.0;                    // s, the analysed state
  BubbleStatistics window;           // over the trailing window (up to RegimeWatch::kWindow)
  Regime shown = Regime::fixed;      // the regime the label shows (RegimeLabel: held 1 s)
  double window_s = 0.0;             // s of frames the statistics cover
  double gravity = 9.81;             // m/s^2, for the 2D rise-velocity reference
  FineGrid grid;                     // the analysis' fine grid
  std::vector<int> label;            // per fine cell: an index into regions, or a kCell* value
  std::vector<Bubble> regions;       // the frame's bubbles and jet cavities
  std::vector<int> frames_seen;      // per region: the frames its id has been seen in so far
  int min_track_frames = 3;          // frames a track needs before its velocity is shown
  std::vector<float> edges;          // their outlines, x0 y0 x1 y1 (m)
  std::vector<float> void_fraction;  // per fine cell

  // The region under a point (m), if any: a bubble or the jet cavity.
  const Bubble* region_at(double x, double y) const;
};

// "fixed bed", "bubbling", "slugging", "spouting" (the shown regime); with "?" while the window
// is still short.
std::string regime_words(const BubbleView& v);

// The regime the label shows, from the window's regime at each analysed frame: a new regime is
// shown once it has held for kHold of simulated time without a break, so the label never flips
// within a second (the paper's bed at 2.8 m/s changes between bubbling and slugging every few
// frames) and a change that lasts is shown a second after it began.
class RegimeLabel {
 public:
  static constexpr double kHold = 1.0;  // s
  // The window's regime at simulated time t (s, increasing); returns the regime shown.
  Regime update(double t, Regime raw);
  Regime shown() const { return shown_; }
  void restart() { *this = RegimeLabel(); }

 private:
  bool started_ = false;
  Regime shown_ = Regime::fixed, candidate_ = Regime::fixed;
  double since_ = 0.0;  // s, when the candidate began
};

// What the pointer's tooltip says of a region's motion. A rise velocity is shown only for a
// bubble (not the jet's cavity) tracked cleanly over at least `min_track_frames` frames whose
// centroid moves up; otherwise the words say why there is none (a velocity of one or two frames
// is the threshold's flicker, a centroid moving down is a void collapsing or its roof falling).
struct RiseShown {
  bool shown = false;
  double vy = 0.0;    // m/s, when shown (> 0)
  std::string words;  // for the tooltip
};
RiseShown rise_shown(const Bubble& b, int frames_seen, int min_track_frames);

// The panel's words for the bubbles' mean rise velocity over the window: the mean of the lasting
// tracks' samples when it is upwards, else words that say the voids did not rise on average;
// empty without samples.
std::string mean_rise_words(const BubbleStatistics& w);

class RegimeWatch {
 public:
  static constexpr double kWindow = 1.0;  // s: the regime of the last second, as run's timeseries

  // Analyses the starting state `sim` is in.
  RegimeWatch(const Settings& scene, const Simulation& sim);
  // After every step: analyses the state when a frame is due; true when it did.
  bool after_step(const Simulation& sim);
  // The bed was reset: tracking starts again from this state (a frame, as `run --bubbles`
  // analyses the start).
  void restart(const Simulation& sim);
  std::shared_ptr<const BubbleView> view() const { return view_; }

 private:
  void analyse(const Simulation& sim);

  BubbleSettings settings_;
  BedGeometry geometry_;
  std::int64_t every_ = 1;  // steps between frames
  std::unique_ptr<BubbleAnalysis> analysis_;
  RegimeLabel label_;
  double started_ = 0.0;  // s, the analysis' first frame
  std::shared_ptr<const BubbleView> view_;
};

}  // namespace fluidbed::app
