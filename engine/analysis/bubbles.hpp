#pragma once
// Bubbles and slugs, measured (model.md 6; issue 15): detection on the fine void-fraction grid,
// tracking from frame to frame with events, statistics over a window and the flow regime.
// (bubbles.cpp: settings, detection, tracking, the per-frame driver; bubble_statistics.cpp:
// statistics, the regime, the history's checkpoint, bubbles.csv.)
//
// Detection. A cell is void when its window void fraction (void_fraction.hpp: eps over a square
// sample window, 2.5 particle diameters by default, centred on each fine cell) exceeds the
// threshold; the window, not the single fine cell, because a fine cell resolves single spheres
// and a bubble with particles raining through it would read as a sieve of fragments. Void cells
// are joined into regions by 4-connectivity (edge neighbours), dense cells into the bed by
// 8-connectivity: the pair is the digital-topology dual, so an 8-connected ring of dense cells
// one cell thin (a bubble's roof about to break) closes a void region, and a bubble is never
// joined to the freeboard or to another bubble through a diagonal chink where two dense cells
// meet at a corner. Two bubbles whose regions share an edge are one bubble.
//   The freeboard: every void region that reaches the top of the domain (or the empty row above
//   the highest sphere). A region open to the freeboard is not a bubble: it is the freeboard.
//   The bed surface, per fine column, from the void fraction: the top of the highest dense cell
//   of that column belonging to the bed, the bed being the 8-connected dense regions that hold at
//   least bed_min_fraction of all dense cells (splashed clusters in the freeboard are smaller;
//   the particle piston above a wall-to-wall slug is not). From the void fraction rather than
//   the particles (the highest centre per column) because one splashed particle would lift the
//   latter by centimetres. A void region whose centroid lies above the surface of its column (a
//   pocket between splashed particles) counts as freeboard, not as a bubble.
//   The jet cavity: a region with a cell in the bottom row over a jet slot (its columns overlap
//   [centre - width/2, centre + width/2]) is flagged touches_jet and is not a formed bubble;
//   when it reaches the freeboard the jet is spouting in that frame (the jet cavity reaches the
//   bed surface).
//   A bubble (or jet cavity) must have D_e = sqrt(4 A / pi) >= min_diameter.
//
// Tracking. Each bubble and jet cavity of a frame is matched to those of the previous frame by
// the overlap of their cells, the previous region shifted by its last velocity times the time
// between the frames (rounded to cells): overlap needs no distance scale and sees coalescence
// and splitting directly; the prediction keeps a fast, small bubble overlapping itself. A
// previous bubble and a new one left without any overlap are paired afterwards when the new
// centroid lies within the sum of their D_e of the predicted one (nearest pairs first; not for a
// bubble that has erupted). Rules:
//   - a region inherits the id of its largest-overlap parent when it is that parent's
//     largest-overlap child; otherwise it gets a new id;
//   - events of a bubble (never of a jet cavity): `formed` when its parent was the jet cavity
//     (detached) or it has no parent (appeared); `coalesced` when it has two or more parents;
//     `split` when it is not its parent's main child (the main child keeps the id);
//   - a previous bubble left without a child has ended: `erupted` when its predicted cells now
//     lie (partly) in the freeboard, or when the bed above it was thinner than the largest D_e
//     its id reached (its roof, at its centroid's column): in the paper's bed a slug near the
//     surface seldom opens a clean hole into the freeboard; its roof rains through it and its
//     gas leaves through the thinned, loosened roof within a few frames, while the surface above
//     falls. `vanished` otherwise (collapsed inside the bed, or shrunk below min_diameter). The
//     final row carries the bubble's last geometry at the time it was found gone;
//   - velocity (vx, vy: centroid displacement over the time between frames) only for a clean
//     one-to-one match of the same kind: a coalescence, a split or a detachment moves the
//     centroid without moving the gas, so those rows have no velocity.
// Slug: a bubble wider than slug_fraction of the bed width.
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
//   fixed     - no bubble was formed and no slug seen in the window (the bed does not bubble:
//               below minimum fluidization a stable jet cavity may stand, but nothing detaches);
//   bubbling  - otherwise.
#include <array>
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/void_fraction.hpp"
#include "dem/particles.hpp"

namespace fluidbed {

// One slot of the gas inlet in the bottom wall.
struct JetSlot {
  double centre = 0.075;  // m, x of the slot's centre
  double width = 0.01;    // m
};

// The slots of `jets` equal jets along the bottom, slot k centred at (k + 1/2) width / jets
// (InletSettings' layout); none for jets <= 0 (a uniform distributor or a closed bottom).
std::vector<JetSlot> jet_slots(double domain_width, int jets, double jet_width);

// What the analysis needs to know of the bed.
struct BedGeometry {
  double width = 0.15;               // m, domain x extent (left wall at x = 0)
  double height = 0.9;               // m, domain y extent (bottom at y = 0)
  double thickness = 0.004;          // m, slab depth
  double particle_diameter = 0.004;  // m, the largest
  double gravity = 9.81;             // m/s^2, for the 2D rise-velocity reference 0.5 sqrt(g D_e)
  std::vector<JetSlot> jets = {JetSlot{}};  // the paper's central 10 mm slot
};

// The scene's [bubbles] section. The defaults are the paper's particle (d = 4 mm); see
// default_bubble_settings for any other diameter.
struct BubbleSettings {
  double threshold = 0.8;       // -, a cell is void when eps > threshold; in (0, 1)
  double min_diameter = 0.008;  // m, smallest D_e of a bubble (2 particle diameters); >= 0
  double cell_size = 0.002;     // m, fine grid (half a particle diameter)
  double window = 0.01;         // m, side of the void fraction's sample window (2.5 d)
  double interval = 0.01;       // s, between frames (the caller's clock); > 0
  double slug_fraction = 0.6;   // -, a bubble wider than this share of the bed width is a slug
  // Statistics (see the top of this file).
  int min_track_frames = 3;   // frames an id must be seen in to count
  double eruption_gap = 0.1;  // s, eruptions closer than this are one burst
  // Regime rule (see the top of this file).
  double slugging_min_fraction = 0.25;  // -, of the frames with a slug
  double spouting_min_fraction = 0.5;   // -, of the frames with the jet open to the freeboard
  // Dense regions smaller than this share of all dense cells are splashes, not the bed.
  double bed_min_fraction = 0.05;  // -
};

// min_diameter = 2 d, cell_size = d / 2 and window = 2.5 d for particles of diameter d; the rest
// as above.
BubbleSettings default_bubble_settings(double particle_diameter);

// Throws InputError with one line naming the key (`bubbles.threshold`, `bubbles.interval`,
// `bubbles.min_diameter`, `bubbles.cell_size`, `bubbles.window`, `bubbles.slug_fraction`, ...).
void validate(const BubbleSettings& s, const BedGeometry& g);

enum class BubbleEvent : std::uint8_t { none, formed, coalesced, split, erupted, vanished };
// "", "formed", "coalesced", "split", "erupted", "vanished": the `event` column of bubbles.csv.
const char* to_string(BubbleEvent e);

// One bubble (or jet cavity) in one frame (plain data; checkpoints write it field by field).
struct Bubble {
  int id = -1;                // tracking id (unique over the run; -1 before tracking)
  double x = 0.0, y = 0.0;    // m, centroid (void-weighted: kCentroidBand)
  double area = 0.0;          // m^2
  double d_eq = 0.0;          // m, sqrt(4 area / pi)
  double width = 0.0;         // m, x extent of its cells
  double height = 0.0;        // m, y extent
  double aspect_ratio = 0.0;  // -, height / width
  double vx = 0.0, vy = 0.0;  // m/s, centroid velocity (when has_velocity)
  double d_eq_max = 0.0;      // m, the largest D_e of this id so far (its parents' included)
  double roof = 0.0;          // m, bed surface at the centroid's column above the region's top
  int cells = 0;              // fine cells
  int i_min = 0, i_max = 0;   // fine columns spanned
  int j_min = 0, j_max = 0;   // fine rows spanned
  bool touches_wall = false;  // a cell in the first or last column
  bool touches_jet = false;   // the jet cavity: a cell in the bottom row over a jet slot
  bool slug = false;          // width > slug_fraction x bed width (never for the jet cavity)
  bool has_velocity = false;  // vx, vy measured (a clean one-to-one match)
  bool from_jet = false;      // event formed: detached from the jet cavity (not appeared)
  BubbleEvent event = BubbleEvent::none;
  int merged_id = -1;  // event coalesced: the id of the largest other parent
};

// Labels of the fine cells (BubbleFrame::label): an index into BubbleFrame::regions, or one of
// these.
constexpr int kCellDense = -1;      // eps <= threshold
constexpr int kCellFreeboard = -2;  // void open to the top, or a pocket above the bed surface
constexpr int kCellSmallVoid = -3;  // void inside the bed, smaller than min_diameter

// The centroid of a bubble weights each cell of it and of its border by
// eps_window - (threshold - kCentroidBand) (see BubbleDetector::weighted_centroid).
constexpr double kCentroidBand = 0.1;

// One analysed frame.
struct BubbleFrame {
  double t = 0.0;               // s
  std::vector<Bubble> regions;  // bubbles and jet cavities (touches_jet), by first cell
  std::vector<Bubble> ended;    // bubbles that ended here (event erupted or vanished)
  std::vector<int> label;       // per fine cell (FineGrid::index): see kCell*
  std::vector<double> surface;  // m, bed surface per fine column (0: no bed there)
  bool spout = false;           // the jet cavity reaches the freeboard
};

// Connected regions, bed surface and jet cavity of one void-fraction field. Holds its scratch
// arrays: no allocation after the first frame.
class BubbleDetector {
 public:
  BubbleDetector(const BubbleSettings& s, const BedGeometry& g);
  // Fills frame.regions (id -1, no velocity, no event), label, surface and spout; frame.t and
  // frame.ended are left alone.
  void detect(const VoidFractionField& field, BubbleFrame& frame);

 private:
  // A connected region of void or dense cells (scratch).
  struct Region {
    int cells = 0;
    double sum_i = 0.0, sum_j = 0.0;  // cell indices summed, for the centroid
    int i_min = 0, i_max = 0, j_min = 0, j_max = 0;
    bool void_cells = true;  // false: a dense region (the bed or a splashed cluster)
    bool touches_top = false, touches_jet = false, touches_wall = false;
  };
  void weighted_centroid(const VoidFractionField& field, const std::vector<int>& label, int k,
                         Bubble& b) const;

  BubbleSettings s_;
  BedGeometry g_;
  std::vector<int> comp_;                       // component per cell
  std::vector<int> class_of_;                   // region class per component
  std::vector<std::array<int, 2>> cell_stack_;  // flood fill: (i, j)
  std::vector<std::uint8_t> void_;              // 1 for eps > threshold
  std::vector<Region> regions_;
  std::vector<std::uint8_t> jet_column_;  // 1 for a fine column over a jet slot
};

// Ids, velocities and events from frame to frame.
class BubbleTracker {
 public:
  BubbleTracker(const BubbleSettings& s, const FineGrid& grid);
  // Matches frame.regions to the previous frame's, sets id, vx, vy, has_velocity, event, and
  // fills frame.ended; then keeps the frame as the previous one. t must increase.
  void track(BubbleFrame& frame);
  const BubbleFrame* previous() const { return has_prev_ ? &prev_ : nullptr; }

  void save(std::ostream& out) const;
  void load(std::istream& in, const std::string& origin);

 private:
  BubbleSettings s_;
  FineGrid grid_;
  BubbleFrame prev_;
  bool has_prev_ = false;
  int next_id_ = 0;
  std::vector<int> overlap_;  // scratch: previous x current
};

enum class Regime : std::uint8_t { fixed, bubbling, slugging, spouting };
const char* to_string(Regime r);  // "fixed", "bubbling", "slugging", "spouting"

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
  };
  std::vector<Frame> frames;    // in time order
  std::vector<Sample> samples;  // in time order
  std::vector<int> id_frames;   // frames each id was seen in, by id

  // Appends a tracked frame (jet cavities count in the frame flags only).
  void add(const BubbleFrame& frame, double dt);
  // Over the frames with t_from < t <= t_to that have a predecessor (dt > 0); gravity for the
  // rise-velocity reference (m/s^2).
  BubbleStatistics summarize(double t_from, double t_to, const BubbleSettings& s,
                             double gravity) const;

  void save(std::ostream& out) const;
  void load(std::istream& in, const std::string& origin);
};

// summary.json's `bubbles` object: the keys of BubbleStatistics with units in their names
// (formed_per_s, eruptions_per_s, mean_d_eq_m, mean_rise_velocity_m_s, slugging_fraction,
// regime, ...); a mean without samples is null.
nlohmann::json to_json(const BubbleStatistics& st);

// One row of bubbles.csv: one per bubble per frame (jet cavities excluded), and one per bubble
// that ended in the frame (erupted or vanished: its last geometry and velocity).
struct BubbleRow {
  double t = 0.0;  // s
  int id = -1;
  double x = 0.0, y = 0.0;           // m
  double d_eq = 0.0;                 // m
  double area = 0.0;                 // m^2
  double width = 0.0, height = 0.0;  // m
  double vx = 0.0, vy = 0.0;         // m/s (when has_velocity; blank in the CSV otherwise)
  bool has_velocity = false;
  BubbleEvent event = BubbleEvent::none;
};

void append_rows(const BubbleFrame& frame, std::vector<BubbleRow>& rows);
// "t,id,x,y,d_eq,area,width,height,vx,vy,event\n"
void write_bubbles_csv_header(std::ostream& out);
void write_bubbles_csv_rows(std::ostream& out, const std::vector<BubbleRow>& rows);

// The outlines of a frame's regions (bubbles and jet cavities): every fine-cell edge between a
// region's cell and a cell outside it, appended to `xy` as x0 y0 x1 y1 (m).
void outline_edges(const BubbleFrame& frame, const FineGrid& grid, std::vector<float>& xy);

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
  // Rows of the last frame (bubbles.csv).
  void append_rows(std::vector<BubbleRow>& rows) const { fluidbed::append_rows(frame_, rows); }
  // Over the frames after averaging_start (to the last frame).
  BubbleStatistics statistics(double averaging_start) const;
  // The regime of the frames in (t_from, t_to]: a timeseries column over a trailing window (an
  // id younger than min_track_frames at the call counts as flicker). Cost: the window's samples
  // (found by bisection), so call it once per frame, not per timeseries row.
  Regime regime(double t_from, double t_to) const;

  // Checkpoints: the tracker and the history (the void fraction and the frame are rebuilt by
  // the next analyse()).
  void save(std::ostream& out) const;
  void load(std::istream& in, const std::string& origin);

 private:
  BubbleSettings s_;
  BedGeometry g_;
  VoidFractionField field_;
  BubbleDetector detector_;
  BubbleTracker tracker_;
  BubbleFrame frame_;
  BubbleHistory history_;
  double last_t_ = 0.0;
  bool started_ = false;
};

}  // namespace fluidbed
