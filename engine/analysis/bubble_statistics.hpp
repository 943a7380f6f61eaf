#pragma once
// What the tracked frames of a run add up to (model.md 6; issue 15): the history kept over the
// run, the statistics over a window, the flow regime, summary.json's `bubbles` object and the
// rows of bubbles.csv.
//
// Statistics over a window (after averaging_start): a frame at time t_k belongs to the window
// when t_k > averaging_start and a frame precedes it; it covers t_k - t_(k-1) of the window's
// duration, and its events happened within that interval. An id seen in fewer than
// min_track_frames frames (over the whole run) is flicker of the threshold, a dilute patch
// crossing 0.8 for a frame or two, and is left out of the counts and means (in the paper's bed at
// 2.8 m/s two thirds of the ids live one or two frames). Means are over bubble-frames (each
// bubble counted once per frame: a time average). Eruptions closer in time than eruption_gap
// are one burst at the surface (the fragments of a collapsing slug end within a few frames of
// one another; the pressure drop sees one surge): eruptions_per_s counts bursts,
// erupted_bubbles_per_s the bubbles. Regime, in this order:
//   spouting  - the jet cavity reaches the freeboard in at least spouting_min_fraction of the
//               frames (default 0.5: most of the time);
//   slugging  - a slug is present in at least slugging_min_fraction of the frames (default 0.25);
//   expanded  - no bubble was formed and no slug seen in the window, but the bed moves and has
//               risen: its surface (the mean over the columns holding bed) stands at least
//               expanded_rise above the run's first frame's, and the particles' median speed is
//               at least expanded_speed, both over the window (a bed fluidized without bubbles,
//               as the teaching bed without damping and friction at 2.8 m/s: 50 mm higher, its
//               median sphere at 0.17 m/s);
//   fixed     - no bubble was formed and no slug seen in the window, and the bed has not both
//               risen and moved (below minimum fluidization a stable jet cavity may stand, but
//               nothing detaches);
//   bubbling  - otherwise.
#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/bubble_types.hpp"
#include "core/binary_io.hpp"

namespace fluidbed {

struct BubbleStatistics {
  double window_start = 0.0;  // s, averaging_start
  double window_end = 0.0;    // s, last frame
  double duration = 0.0;      // s, covered by the window's frames
  int frames = 0;
  // Counts of the ids seen in at least min_track_frames frames (a coalescence: both ids).
  int formed = 0, formed_at_jet = 0, coalesced = 0, split = 0, erupted = 0, vanished = 0;
  int eruption_bursts = 0;              // eruptions grouped by eruption_gap
  double formed_per_s = 0.0;            // 1/s, bubbles formed (detached from the jet or appeared)
  double formed_at_jet_per_s = 0.0;     // 1/s
  double eruptions_per_s = 0.0;         // 1/s, bursts at the surface
  double erupted_bubbles_per_s = 0.0;   // 1/s, bubbles
  double coalescences_per_s = 0.0;      // 1/s
  double splits_per_s = 0.0;            // 1/s
  double mean_bubbles = 0.0;            // bubbles per frame
  int bubble_frames = 0;                // bubbles summed over the frames
  int velocity_samples = 0;             // of those, with a velocity
  int flicker_ids = 0;                  // ids born in the window and left out (too short-lived)
  double mean_d_eq_m = 0.0;             // m, over bubble-frames (NaN when there are none)
  double mean_rise_velocity_m_s = 0.0;  // m/s, mean vy over bubble-frames with a velocity (NaN)
  double mean_vx_m_s = 0.0;             // m/s (NaN)
  // The two-dimensional reference u_b = 0.5 sqrt(g D_e) (Pyle and Harrison 1967) averaged over
  // the same bubble-frames: a reference, not a fit (NaN).
  double mean_rise_velocity_2d_ref_m_s = 0.0;
  double slugging_fraction = 0.0;    // -, frames with a slug
  double spouting_fraction = 0.0;    // -, frames with the jet cavity open to the freeboard
  double jet_cavity_fraction = 0.0;  // -, frames with a jet cavity
  double bed_rise_m = 0.0;  // m, the window's mean bed surface above the reference_surface
  double median_particle_speed_m_s = 0.0;  // m/s, the frames' median particle speed, averaged
  Regime regime = Regime::fixed;
};

Regime classify_regime(const BubbleStatistics& st, const BubbleSettings& s);

// What the statistics are computed from, kept for a whole run (small: one record per frame and
// one per bubble per frame).
struct BubbleHistory {
  struct Frame {
    double t = 0.0;           // s
    double dt = 0.0;          // s since the previous frame (0 for the first)
    bool slug = false;        // a slug present
    bool spout = false;       // the jet cavity reaches the freeboard
    bool jet_cavity = false;  // a jet cavity present
    double surface = 0.0;       // m, mean bed surface over the columns holding bed (0: none)
    double median_speed = 0.0;  // m/s, the particles' median speed

    template <class Archive>
    void fields(Archive& a) {
      a(t, dt, slug, spout, jet_cavity, surface, median_speed);
    }
  };
  struct Sample {    // one bubble in one frame, or one that ended there
    double t = 0.0;  // s
    int id = -1;
    double d_eq = 0.0;          // m
    double vx = 0.0, vy = 0.0;  // m/s
    bool has_velocity = false;
    bool from_jet = false;
    int merged_id = -1;  // event coalesced: the largest other parent
    bool ended = false;  // an erupted or vanished bubble's last record (not a bubble-frame)
    BubbleEvent event = BubbleEvent::none;

    template <class Archive>
    void fields(Archive& a) {
      a(t, d_eq, vx, vy, id, merged_id, has_velocity, from_jet, ended, event);
      a.check(event <= BubbleEvent::vanished, "bubble event");
    }
  };
  std::vector<Frame> frames;    // in time order
  std::vector<Sample> samples;  // in time order
  std::vector<int> id_frames;   // frames each id was seen in, by id
  // m, the bed surface the rise is measured from: the first frame's (< 0 before it), or one
  // carried over from an earlier history of the same run.
  double reference_surface = -1.0;

  // Appends a tracked frame (jet cavities count in the frame flags only).
  void add(const BubbleFrame& frame, double dt);
  // Over the frames with t_from < t <= t_to that have a predecessor (dt > 0); gravity for the
  // rise-velocity reference (m/s^2).
  BubbleStatistics summarize(double t_from, double t_to, const BubbleSettings& s,
                             double gravity) const;
  // Lets go of the records no summary with t_from >= t reads: the frames before the last one at
  // or before t, and the samples at or before t (id_frames and the reference surface stay).
  // Such summaries come out the same to the bit. The records go in batches, once they are at
  // least as many as those kept, so that a caller forgetting at every frame copies each record
  // about once: a trailing window's history stays within twice the window.
  void forget_before(double t);

  // Its state, for a checkpoint (core/binary_io.hpp).
  template <class Archive>
  void fields(Archive& a) {
    a.tag("FLBHIS03", "bubble history");
    a(frames, samples, id_frames, reference_surface);
  }
  void save(BinarySink& out) const { out(*this); }
  void restore(BinarySource& in) { in(*this); }
};

// summary.json's `bubbles` object: the keys of BubbleStatistics with units in their names
// (formed_per_s, eruptions_per_s, mean_d_eq_m, mean_rise_velocity_m_s, slugging_fraction,
// regime, ...); a mean without samples is null.
nlohmann::json to_json(const BubbleStatistics& st);

// The rows of bubbles.csv (BubbleRow) of a tracked frame, appended to `rows`.
void append_rows(const BubbleFrame& frame, std::vector<BubbleRow>& rows);
// "t,id,x,y,d_eq,area,width,height,vx,vy,event\n"
void write_bubbles_csv_header(std::ostream& out);
void write_bubbles_csv_rows(std::ostream& out, const std::vector<BubbleRow>& rows);

}  // namespace fluidbed
