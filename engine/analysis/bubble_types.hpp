#pragma once
// The plain data of the bubble analysis (analysis/bubbles.hpp): the bed as the analysis sees it,
// the scene's [bubbles] settings, one bubble in one frame, a frame, the regime and a row of
// bubbles.csv. What the fields mean in detection, tracking and statistics is said in
// bubble_detector.hpp, bubble_tracker.hpp and bubble_statistics.hpp.
#include <cstdint>
#include <vector>

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
  // Statistics (see analysis/bubble_statistics.hpp).
  int min_track_frames = 3;   // frames an id must be seen in to count
  double eruption_gap = 0.1;  // s, eruptions closer than this are one burst
  // Regime rule (see analysis/bubble_statistics.hpp).
  double slugging_min_fraction = 0.25;  // -, of the frames with a slug
  double spouting_min_fraction = 0.5;   // -, of the frames with the jet open to the freeboard
  // A bed without bubbles is expanded, not fixed, when its surface stands at least expanded_rise
  // above the first frame's and its median particle moves at least expanded_speed (one diameter
  // and one diameter a second).
  double expanded_rise = 0.004;   // m
  double expanded_speed = 0.004;  // m/s
  // Dense regions smaller than this share of all dense cells are splashes, not the bed.
  double bed_min_fraction = 0.05;  // -
};

// min_diameter = 2 d, cell_size = d / 2, window = 2.5 d, expanded_rise = d and expanded_speed =
// d per second for particles of diameter d; the rest as above.
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

  // Its saved state (core/binary_io.hpp).
  template <class Archive>
  void fields(Archive& a) {
    a(id, merged_id, x, y, area, d_eq, width, height, aspect_ratio, vx, vy, d_eq_max, roof, cells,
      i_min, i_max, j_min, j_max, touches_wall, touches_jet, slug, has_velocity, from_jet, event);
    a.check(event <= BubbleEvent::vanished, "bubble event");
  }
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
  double median_speed = 0.0;    // m/s, the particles' median speed
};

enum class Regime : std::uint8_t { fixed, bubbling, slugging, spouting, expanded };
const char* to_string(Regime r);  // "fixed", "bubbling", "slugging", "spouting", "expanded"

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

}  // namespace fluidbed
