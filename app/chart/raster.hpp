#pragma once
// Anti-aliased shapes for the charts (internal to fluidbed_chart).
//
// A shape is first drawn as coverage (0..1 per pixel, the largest where pieces overlap), then
// blended into the image once in one colour. So the joints of a polyline and the overlaps of its
// dashes are not blended twice and darker; and a clip box bounds everything drawn.
#include <vector>

#include "chart/chart.hpp"

namespace fluidbed::chart::detail {

struct Point {
  double x, y;  // px
};

class Coverage {
 public:
  Coverage(int width, int height);

  // Nothing is drawn outside CLIP (px, rounded outward to whole pixels); the whole image at first.
  void set_clip(const Box& clip);
  void reset_clip();

  // A line of WIDTH px with round ends.
  void segment(Point a, Point b, double width);
  // Joined segments; DASH > 0 draws DASH px on, GAP px off, continuing around corners.
  void polyline(const std::vector<Point>& points, double width, double dash = 0.0,
                double gap = 0.0);
  // An axis-aligned rectangle; partially covered edge pixels get partial coverage.
  void rect(const Box& box);
  // A marker of SIZE px across centred at C; RING > 0 keeps only a band of RING px inside the
  // outline (an open marker).
  void marker(Point c, double size, Shape shape, double ring = 0.0);

  // Blends the coverage into IMAGE in COLOUR (times OPACITY) and clears it.
  void composite(Image& image, Rgb colour, float opacity = 1.0F);

 private:
  void put(int x, int y, float a);
  template <class SignedDistance>
  void fill(double x0, double y0, double x1, double y1, SignedDistance sd);

  int width_, height_;
  std::vector<float> a_;
  int clip_x0_, clip_y0_, clip_x1_, clip_y1_;  // half-open, whole pixels
  int dirty_x0_, dirty_y0_, dirty_x1_, dirty_y1_;
};

}  // namespace fluidbed::chart::detail
