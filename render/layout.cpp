#include "render/layout.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed::render {
namespace {

// Text sizes, margins and the vertical extent of the beds for a picture `height` px tall, with
// `below` font heights kept free under the bed (jet marker, time labels).
FrameLayout vertical_metrics(int width, int height, float below) {
  FrameLayout l;
  l.width = width;
  l.height = height;
  const auto h = static_cast<float>(height);
  // Text follows the shorter side, so a portrait frame keeps room beside the bed for its labels.
  const float side = width > 0 ? std::min(h, static_cast<float>(width)) : h;
  l.font = std::max(10.0f, std::round(side / 40.0f));
  l.small = std::round(l.font * 0.8f);
  l.big = std::round(l.font * 1.35f);
  l.margin = std::max(6.0f, std::round(h * 0.03f));
  l.wall = std::max(2.0f, std::round(h / 360.0f));
  l.info.y0 = l.margin;
  l.info.y1 = h - l.margin - below * l.font;
  return l;
}

// The information column: about 16 font widths, room for "U = 2.80 m/s (jet 42.0 m/s)".
float info_width(const FrameLayout& l) {
  return 16.0f * l.font;
}

void place_info(FrameLayout& l, float x0) {
  l.info.x0 = x0;
  l.info.x1 = x0 + info_width(l);
  const float bed_h = l.beds.front().inside.height();
  // Below four lines of text and the colour bar's title.
  l.colour_bar.x0 = x0;
  l.colour_bar.x1 = x0 + l.font;
  l.colour_bar.y0 = l.info.y0 + 7.8f * l.font;
  l.colour_bar.y1 = l.colour_bar.y0 + std::max(4.0f * l.font, 0.4f * bed_h);
}

// The panel a bed's walls enclose (the jet's arrow below them left out).
Rect walled(const Rect& in, float wall) {
  return {in.x0 - wall, in.y0 - wall, in.x1 + wall, in.y1 + wall};
}

}  // namespace

FrameLayout frame_layout(const Snapshot& s, int width, int height, double close_up,
                         bool caption_band) {
  FrameLayout l = vertical_metrics(width, height, 1.6f);
  if (caption_band) {
    // Two lines of the caption's text (big) with a little air.
    l.caption = {0.0f, 0.0f, static_cast<float>(width), std::round(3.1f * l.big)};
    l.info.y0 += l.caption.y1;
  }
  const float top = l.info.y0 + l.wall, bottom = l.info.y1 - l.wall;
  const float gap = 2.0f * l.font;
  const bool zoom = close_up > 0.0 && close_up < 1.0;
  // The close-up starts lower, leaving a line for its label above it.
  const float zoom_top = top + 1.6f * l.font;
  double scale = (bottom - top) / std::max(s.height, 1e-9);
  double zoom_scale = zoom ? (bottom - zoom_top) / std::max(close_up * s.height, 1e-9) : 0.0;
  // Shrink both panels alike when the frame is too narrow for them and the labels.
  const float fixed =
      2.0f * l.margin + gap + info_width(l) + (zoom ? 4.0f * l.wall + gap : 2.0f * l.wall);
  const double needed = s.width * (scale + zoom_scale);
  const double avail = static_cast<double>(width) - fixed;
  if (avail > 0.0 && needed > avail) {
    scale *= avail / needed;
    zoom_scale *= avail / needed;
  }
  const auto bed_w = static_cast<float>(s.width * scale);
  const auto zoom_w = static_cast<float>(s.width * zoom_scale);
  const float content = fixed - 2.0f * l.margin + bed_w + zoom_w;
  float x = std::max(l.margin, std::round((static_cast<float>(width) - content) / 2.0f)) + l.wall;
  BedView bed;
  bed.scale = scale;
  // Both beds stand on the same floor (a frame too narrow shrinks them).
  bed.inside = {x, bottom - static_cast<float>(s.height * scale), x + bed_w, bottom};
  bed.clip = walled(bed.inside, l.wall);
  l.beds.push_back(bed);
  x = bed.inside.x1 + l.wall;
  if (zoom) {
    x += gap + l.wall;
    BedView z;
    z.scale = zoom_scale;
    z.inside = {x, bottom - static_cast<float>(close_up * s.height * zoom_scale), x + zoom_w,
                bottom};
    z.clip = walled(z.inside, l.wall);
    z.clip.y0 = z.inside.y0;  // the close-up is cut at its top, not walled
    l.beds.push_back(z);
    l.close_up_height = close_up * s.height;
    x = z.inside.x1 + l.wall;
  }
  place_info(l, x + gap);
  return l;
}

bool keeps_close_up(const Snapshot& s, int width, int height, double close_up, bool caption_band) {
  if (!(close_up > 0.0 && close_up < 1.0)) return false;
  const double both = frame_layout(s, width, height, close_up, caption_band).beds.front().scale;
  const double alone = frame_layout(s, width, height, 0.0, caption_band).beds.front().scale;
  return both >= kCloseUpKeep * alone;
}

FrameLayout montage_layout(const Snapshot& s, int panels, int height) {
  FrameLayout l = vertical_metrics(0, height, 3.0f);
  const float top = l.info.y0 + l.wall, bottom = l.info.y1 - l.wall;
  const double scale = (bottom - top) / std::max(s.height, 1e-9);
  const auto bed_w = static_cast<float>(s.width * scale);
  const auto bed_h = static_cast<float>(s.height * scale);
  // Panels a little wider than the bed so that the time labels ("t = 0.60 s") fit between them.
  const float panel = std::max(bed_w + 2.0f * l.wall + 1.5f * l.font, 6.0f * l.font);
  for (int i = 0; i < panels; ++i) {
    BedView bed;
    bed.scale = scale;
    const float left = l.margin + static_cast<float>(i) * panel + (panel - bed_w) / 2.0f;
    bed.inside = {std::round(left), top, std::round(left) + bed_w, top + bed_h};
    bed.clip = walled(bed.inside, l.wall);
    l.beds.push_back(bed);
  }
  l.label_y = bottom + l.wall + 2.6f * l.font;
  place_info(l, l.margin + static_cast<float>(panels) * panel + l.font);
  l.width = static_cast<int>(std::ceil(l.info.x1 + l.margin));
  l.width += l.width % 2;  // even, like the frames a video needs
  return l;
}

void zoom_bed(FrameLayout& l, const BedZoom& z) {
  if (z.bed < 0 || z.bed >= static_cast<int>(l.beds.size()) || !(z.factor > 1.0)) return;
  BedView& b = l.beds[static_cast<std::size_t>(z.bed)];
  // The metres the panel shows unzoomed, and the panel.
  const double w = b.inside.width() / b.scale, h = b.inside.height() / b.scale;
  const Rect panel = b.inside;
  const double scale = b.scale * z.factor;
  const double half_w = 0.5 * panel.width() / scale, half_h = 0.5 * panel.height() / scale;
  const double x = std::clamp(z.x, half_w, std::max(half_w, w - half_w));
  const double y = std::clamp(z.y, half_h, std::max(half_h, h - half_h));
  const double cx = 0.5 * (panel.x0 + panel.x1), cy = 0.5 * (panel.y0 + panel.y1);
  b.scale = scale;
  b.inside.x0 = static_cast<float>(cx - x * scale);
  b.inside.x1 = static_cast<float>(cx + (w - x) * scale);
  b.inside.y1 = static_cast<float>(cy + y * scale);
  b.inside.y0 = static_cast<float>(cy - (h - y) * scale);
  b.zoomed = true;
}

}  // namespace fluidbed::render
