#pragma once
// Text for the charts (internal to fluidbed_chart): UTF-8 strings set in one font with
// stb_truetype, anti-aliased, glyph bitmaps cached per size and quarter-pixel offset.
#include <map>
#include <string_view>
#include <tuple>
#include <vector>

#include "chart/chart.hpp"

namespace fluidbed::chart::detail {

enum class Align { Start, Centre, End };  // along the line of text
enum class Anchor {
  Top,
  Middle,
  Baseline,
  Bottom
};  // across it: cap top, half cap, baseline,
    // descender bottom

// One painter per drawing: the cache is not shared between threads.
class TextPainter {
 public:
  explicit TextPainter(const Font& font);

  // All in px for a font of SIZE px (ascender to descender).
  double width(std::string_view utf8, double size) const;
  double cap_height(double size) const;
  double descent(double size) const;  // below the baseline, positive
  double height(double size) const { return cap_height(size) + descent(size); }

  // Draws UTF8 with its anchor point at (X, Y); VERTICAL reads upward (a y-axis label), and
  // then ALIGN runs along the vertical. Returns the box it covers.
  Box draw(Image& image, std::string_view utf8, double x, double y, double size, Rgb colour,
           Align align, Anchor anchor, bool vertical = false);
  // The box draw would cover, without drawing.
  Box bounds(std::string_view utf8, double x, double y, double size, Align align, Anchor anchor,
             bool vertical = false) const;

 private:
  struct Glyph {
    int x0 = 0, y0 = 0, w = 0, h = 0;  // px from the pen on the baseline
    std::vector<unsigned char> alpha;
  };
  struct Placed {
    int glyph;
    double pen;  // px from the start of the line
  };
  std::vector<Placed> shape(std::string_view utf8, double size, double* advance) const;
  const Glyph& glyph(int index, double size, int quarter);
  // Where the text's own frame (u along, v across, from the anchor) puts its origin.
  void origin(double advance, double size, Align align, Anchor anchor, int* u0, int* base) const;

  const Font::Data* font_;
  std::map<std::tuple<long, int, int>, Glyph> cache_;
};

}  // namespace fluidbed::chart::detail
