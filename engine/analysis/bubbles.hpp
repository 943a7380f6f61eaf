#pragma once
// Bubbles and slugs, measured (model.md 6; issue 15), one frame at a time: the void fraction of
// the particles on a fine grid, the regions found in it, tracked from frame to frame with events,
// and the statistics over a window with the flow regime. This header is the whole analysis for
// the run loop (BubbleAnalysis); its parts, each with what it means:
//   analysis/bubble_types.hpp       the plain data: settings, bed geometry, a bubble, a frame,
//                                   the regime, a row of bubbles.csv
//   analysis/void_fraction.hpp      the fine grid's void fraction and its sample window
//   analysis/bubble_detector.hpp    detection: void regions, bed surface, jet cavity, slugs
//   analysis/bubble_tracker.hpp     tracking: ids, velocities and events from frame to frame
//   analysis/bubble_statistics.hpp  the history of a run, the statistics over a window, the
//                                   regime, summary.json's `bubbles` and bubbles.csv
#include <vector>

#include "analysis/bubble_detector.hpp"
#include "analysis/bubble_statistics.hpp"
#include "analysis/bubble_tracker.hpp"
#include "analysis/bubble_types.hpp"
#include "analysis/void_fraction.hpp"
#include "core/binary_io.hpp"
#include "dem/particles.hpp"

namespace fluidbed {

// Everything per frame, for the run loop: void fraction, detection, tracking and the per-frame
// summaries. Call analyse() once per interval with increasing t.
class BubbleAnalysis {
 public:
  // Validates the settings (InputError).
  BubbleAnalysis(const BubbleSettings& s, const BedGeometry& g);

  const BubbleFrame& analyse(double t, const Particles& p);

  const BubbleSettings& settings() const { return s_; }
  const BedGeometry& geometry() const { return g_; }
  const VoidFractionField& void_fraction() const { return field_; }
  const BubbleFrame& frame() const { return frame_; }  // the last analysed
  const BubbleHistory& history() const { return history_; }
  // Measures the bed's rise from `surface` (m; see BubbleHistory::reference_surface): an analysis
  // started again in the same run keeps the first one's.
  void set_reference_surface(double surface) { history_.reference_surface = surface; }
  // Rows of the last frame (bubbles.csv).
  void append_rows(std::vector<BubbleRow>& rows) const { fluidbed::append_rows(frame_, rows); }
  // Over the frames after averaging_start (to the last frame).
  BubbleStatistics statistics(double averaging_start) const;
  // The regime of the frames in (t_from, t_to]: a timeseries column over a trailing window (an
  // id younger than min_track_frames at the call counts as flicker). Cost: the window's samples
  // (found by bisection), so call it once per frame, not per timeseries row.
  Regime regime(double t_from, double t_to) const;
  // Lets go of the history no later summary reads (BubbleHistory::forget_before): for a caller
  // that only ever looks at a trailing window from `t` on (the viewer's regime), whose run may
  // last hours.
  void forget_before(double t) { history_.forget_before(t); }

  // Its state for a checkpoint (core/binary_io.hpp): the tracker and the history (the void
  // fraction and the frame are rebuilt by the next analyse()). restore expects an analysis built
  // with the same settings and geometry that has not analysed yet.
  template <class Archive>
  void fields(Archive& a) {
    a.tag("FLBBUB03", "bubble analysis");
    a(tracker_, started_, last_t_, history_);
  }
  void save(BinarySink& out) const { out(*this); }
  void restore(BinarySource& in) { in(*this); }

 private:
  BubbleSettings s_;
  BedGeometry g_;
  VoidFractionField field_;
  BubbleDetector detector_;
  BubbleTracker tracker_;
  BubbleFrame frame_;
  BubbleHistory history_;
  std::vector<double> speeds_;  // median_speed's scratch
  double last_t_ = 0.0;
  bool started_ = false;
};

}  // namespace fluidbed
