#pragma once
// Bubbles followed from frame to frame (model.md 6; issue 15): ids, velocities and events of the
// regions bubble_detector.hpp finds.
//
// Each bubble and jet cavity of a frame is matched to those of the previous frame by the overlap
// of their cells, the previous region shifted by its last velocity times the time between the
// frames (rounded to cells): overlap needs no distance scale and sees coalescence and splitting
// directly; the prediction keeps a fast, small bubble overlapping itself. A previous bubble and
// a new one left without any overlap are paired afterwards when the new centroid lies within the
// sum of their D_e of the predicted one (nearest pairs first; not for a bubble that has
// erupted). Rules:
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
#include <cstddef>
#include <vector>

#include "analysis/bubble_types.hpp"
#include "analysis/void_fraction.hpp"
#include "core/binary_io.hpp"

namespace fluidbed {

// Ids, velocities and events from frame to frame.
class BubbleTracker {
 public:
  BubbleTracker(const BubbleSettings& s, const FineGrid& grid);
  // Matches frame.regions to the previous frame's, sets id, vx, vy, has_velocity, event, and
  // fills frame.ended; then keeps the frame as the previous one. t must increase.
  void track(BubbleFrame& frame);
  const BubbleFrame* previous() const { return has_prev_ ? &prev_ : nullptr; }

  // Its state (the previous frame and the next id), for a checkpoint (core/binary_io.hpp).
  // restore expects a tracker built for the same grid that has not tracked yet, and refuses a
  // state whose arrays do not fit the grid.
  template <class Archive>
  void fields(Archive& a) {
    a.tag("FLBTRK02", "bubble tracker");
    a(has_prev_, next_id_, prev_.t, prev_.spout, prev_.regions, prev_.label, prev_.surface);
    const auto cells = static_cast<std::size_t>(grid_.cells());
    a.check(prev_.regions.size() <= cells, "bubble count");
    a.check(!has_prev_ || (prev_.label.size() == cells &&
                           prev_.surface.size() == static_cast<std::size_t>(grid_.nx)),
            "array sizes");
  }
  void save(BinarySink& out) const { out(*this); }
  void restore(BinarySource& in) { in(*this); }

 private:
  BubbleSettings s_;
  FineGrid grid_;
  BubbleFrame prev_;
  bool has_prev_ = false;
  int next_id_ = 0;
  std::vector<int> overlap_;  // scratch: previous x current
};

}  // namespace fluidbed
