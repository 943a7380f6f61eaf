#pragma once
// Where things go in a frame or a montage, in pixels (y down): the bed panels, the labels, the
// colour bar. Pure arithmetic on the snapshot's domain size and the picture's size, so tests can
// say on which pixels a particle at (x, y) must land.
#include <vector>

#include "sim/snapshot.hpp"

namespace fluidbed::render {

struct Rect {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  float width() const { return x1 - x0; }
  float height() const { return y1 - y0; }
};

// One bed drawn in a panel: the inside of its walls, and the map from metres to pixels (aspect
// kept; the bed's height fits the panel). Zoomed (zoom_bed), `inside` grows beyond the panel and
// `clip` keeps the panel's place: what lies outside it is not drawn.
struct BedView {
  Rect inside;
  Rect clip;           // the panel, walls included
  double scale = 1.0;  // px per m
  bool zoomed = false;
  float px(double x) const { return inside.x0 + static_cast<float>(x * scale); }
  float py(double y) const { return inside.y1 - static_cast<float>(y * scale); }
};

// A bed panel shown magnified (the viewer's zoom): `factor` >= 1 about the point (x, y) in
// metres, which is shown at the panel's centre (moved in as far as needed to keep the view
// inside the bed).
struct BedZoom {
  int bed = -1;  // index into FrameLayout::beds; < 0: no zoom
  double factor = 1.0;
  double x = 0.0, y = 0.0;  // m
};

struct FrameLayout {
  int width = 0, height = 0;              // px
  float font = 12, small = 10, big = 16;  // text sizes (px)
  float margin = 8, wall = 2;             // px
  std::vector<BedView> beds;              // one per panel (a frame: the bed, then its close-up)
  double close_up_height = 0.0;           // m: the close-up shows the bed from 0 to this height
  float label_y = 0;                      // montage: baseline of the time under each panel
  Rect info;                              // the text block, colour bar and legends
  Rect colour_bar;
  Rect caption;  // the band over the beds kept for a caption (or empty)
};

// A frame of width x height showing one snapshot: the whole bed on the left; with `close_up` in
// (0, 1), beside it the bed's lower `close_up` of its height, magnified to the same panel height
// (bubbles and the jet cavity, large); the labels on the right.
// With `caption_band`, a band two text lines high is kept across the top for a caption (the
// viewer and lessons keep it always, so the beds do not move when a caption comes or goes).
FrameLayout frame_layout(const Snapshot& s, int width, int height, double close_up = 0.0,
                         bool caption_band = false);
// Whether a window's frame keeps the close-up: a frame too narrow for both panels at the bed's
// full height shrinks them alike, and the close-up is kept while the whole bed keeps at least
// kCloseUpKeep of the height it has alone (below that the beds shrink towards slivers; at 2/3 a
// 1000 x 650 window keeps it, its beds 75 % tall, where 0.8 dropped it).
inline constexpr double kCloseUpKeep = 2.0 / 3.0;
bool keeps_close_up(const Snapshot& s, int width, int height, double close_up, bool caption_band);
// Magnifies one bed panel of `l` (see BedZoom); nothing for a zoom of 1 or a bed out of range.
void zoom_bed(FrameLayout& l, const BedZoom& z);
// Several snapshots side by side (`panels` of them, same domain), each `height` px tall with its
// time under it, the labels and colour bar on the right. The width follows.
FrameLayout montage_layout(const Snapshot& s, int panels, int height);

}  // namespace fluidbed::render
