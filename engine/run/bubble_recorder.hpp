#pragma once
// What `run --bubbles` records beside the timeseries: one bubble analysis every
// [bubbles] interval (analysis/bubbles.hpp: detection, tracking, events), its rows for
// bubbles.csv, the Lacey mixing index of the two halves of the bed by initial height at the same
// times (analysis/mixing.hpp), and the regime over a trailing window for the timeseries.
#include <cstdint>
#include <optional>
#include <vector>

#include "analysis/bubbles.hpp"
#include "analysis/mixing.hpp"
#include "core/binary_io.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot.hpp"

namespace fluidbed {

// The analysis settings of a scene: its [bubbles] section, lengths of 0 scaled by the diameter.
BubbleSettings bubble_settings_for(const Settings& s);
// The bed as the analysis sees it: the domain, the jets (none without a jet inlet), the particle
// diameter and gravity.
BedGeometry bubble_geometry_for(const Settings& s);

// The analysis of the state `sim` is in, written into the snapshot for pictures (frames,
// montages, the viewer, VTK): the fine void fraction and the outlines of the regions found.
void add_bubble_fields(BubbleAnalysis& analysis, const Simulation& sim, Snapshot& s);
// The same from the frame `analysis` found last, for a state it has analysed already.
void add_bubble_fields(const BubbleAnalysis& analysis, Snapshot& s);

struct MixingSample {
  double t = 0.0;      // s
  double index = 0.0;  // Lacey's M (NaN where it is undefined)
};

class BubbleRecorder {
 public:
  // The regime column of the timeseries is the regime of the frames in this trailing window (s).
  static constexpr double kRegimeWindow = 1.0;

  explicit BubbleRecorder(const Simulation& sim);
  // After every step: analyses a frame when one is due (every [bubbles] interval, counted in
  // steps from the start of the run, the start itself included).
  void after_step(const Simulation& sim);
  void analyse(const Simulation& sim);

  const std::vector<BubbleRow>& rows() const { return rows_; }
  std::vector<BubbleRow> take_rows() { return std::move(rows_); }
  const std::vector<MixingSample>& mixing() const { return mixing_; }
  // Bubbles (not jet cavities) in the last frame, and the regime of the trailing window.
  int bubbles_now() const { return bubbles_now_; }
  Regime regime_now() const { return regime_now_; }
  // summary.json's `bubbles` and `mixing` objects (statistics after averaging_start).
  nlohmann::json bubbles_summary(double averaging_start) const;
  nlohmann::json mixing_summary() const;

  // Its state, for a run's checkpoint (run/checkpoint.hpp, core/binary_io.hpp): the tracker and
  // history of the analysis, the rows and mixing samples so far, the last frame's counts. restore
  // expects a recorder built for the same scene and refuses one analysed at another interval.
  template <class Archive>
  void fields(Archive& a) {
    a.tag("FLBBRC02", "bubble recorder");
    const std::int64_t every = every_;
    a(analysis_, every_, bubbles_now_, regime_now_, rows_, mixing_);
    a.check(every_ == every, "bubble analysis interval");
    a.check(regime_now_ <= Regime::expanded, "bubble regime");
  }
  void save(BinarySink& out) const { out(*this); }
  void restore(BinarySource& in) { in(*this); }

 private:
  BubbleAnalysis analysis_;
  std::int64_t every_ = 1;  // steps between frames
  std::vector<std::uint8_t> kind_;
  double width_, height_;
  std::vector<BubbleRow> rows_;
  std::vector<MixingSample> mixing_;
  int bubbles_now_ = 0;
  Regime regime_now_ = Regime::fixed;
};

}  // namespace fluidbed
