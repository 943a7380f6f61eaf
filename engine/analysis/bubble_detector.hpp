#pragma once
// Bubbles found in one frame (model.md 6; issue 15): connected regions of a void-fraction field,
// the bed surface and the jet cavity. (Tracking from frame to frame: bubble_tracker.hpp.)
//
// A cell is void when its window void fraction (void_fraction.hpp: eps over a square sample
// window, 2.5 particle diameters by default, centred on each fine cell) exceeds the threshold;
// the window, not the single fine cell, because a fine cell resolves single spheres and a bubble
// with particles raining through it would read as a sieve of fragments. Void cells are joined
// into regions by 4-connectivity (edge neighbours), dense cells into the bed by 8-connectivity:
// the pair is the digital-topology dual, so an 8-connected ring of dense cells one cell thin (a
// bubble's roof about to break) closes a void region, and a bubble is never joined to the
// freeboard or to another bubble through a diagonal chink where two dense cells meet at a
// corner. Two bubbles whose regions share an edge are one bubble.
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
// Slug: a bubble wider than slug_fraction of the bed width.
#include <array>
#include <cstdint>
#include <vector>

#include "analysis/bubble_types.hpp"
#include "analysis/void_fraction.hpp"

namespace fluidbed {

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

// The outlines of a frame's regions (bubbles and jet cavities): every fine-cell edge between a
// region's cell and a cell outside it, appended to `xy` as x0 y0 x1 y1 (m).
void outline_edges(const BubbleFrame& frame, const FineGrid& grid, std::vector<float>& xy);

}  // namespace fluidbed
