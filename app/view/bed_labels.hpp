#pragma once
// The presenter mode's words in the bed (`view --present`, the `p` key): where the jet, the
// bubbles, a slug, the dead zones beside a jet and the freeboard are, found in the last bubble
// analysis and the particles' motion. No ImGui, so tests can read them.
#include <string>
#include <vector>

#include "sim/snapshot.hpp"
#include "view/regime_watch.hpp"

namespace fluidbed::app {

struct BedLabel {
  std::string text;         // "jet", "bubble", "slug", "dead zone", "freeboard"
  double x = 0.0, y = 0.0;  // m, where the word's centre goes
};

// The rules, each from what the analysis found, never from the scene's name:
// - "jet": the centroid of each region the analysis calls the jet's cavity (touches_jet);
// - "slug": each region wider than the analysis' slug fraction of the bed;
// - "bubble": the kMaxBubbleLabels largest other regions, at their centroids;
// - "freeboard": the gas above the bed surface (the lowest fine row from which every row up is at
//   least kFreeboardShare freeboard cells), when it is at least kFreeboardRoom of the height;
// - "dead zone": a bottom corner box (kCornerShare of the width wide and as high, at most a third
//   of the bed's height) beside a jet cavity whose particles' mean speed is below kDeadShare of
//   the whole bed's mean speed, while the bed moves (its mean speed above kMovingSpeed).
inline constexpr int kMaxBubbleLabels = 3;
inline constexpr double kFreeboardShare = 0.9;
inline constexpr double kFreeboardRoom = 0.08;
inline constexpr double kCornerShare = 0.2;
// Measured on the paper's bed at 2.8 m/s (t = 1.5, 2, 2.5 s): the bottom corners' spheres move at
// 0.03 to 0.4 of the bed's mean speed (a slug's collapse sweeps a corner now and then), the
// teaching bed's at 0.1 to 0.25; below 1.8 m/s the whole bed rests.
inline constexpr double kDeadShare = 0.2;
inline constexpr double kMovingSpeed = 0.02;  // m/s

std::vector<BedLabel> bed_labels(const Snapshot& s, const BubbleView& v);

// m: the bed surface the freeboard rule finds (the grid's height when the bed fills it).
double bed_surface(const BubbleView& v);

}  // namespace fluidbed::app
