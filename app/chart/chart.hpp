#pragma once
// Charts drawn to PNG by the program itself: line and marker series on linear or log axes,
// reference lines, error bars, labelled points, a legend, and figures of several panels.
// Text comes from stb_truetype, PNG files from the program's writer (render/image.hpp), tick
// values from render/ticks.hpp; no GL. Same input, same bytes.
//
// Sizes given in px (line widths, marker sizes) are px of an 800 x 500 chart. A bigger image
// scales them, and the text, by min(width / 800, height / 500): a 1600 x 1000 chart looks like
// the 800 x 500 one at twice the resolution.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/font_file.hpp"
#include "render/ticks.hpp"

namespace fluidbed::chart {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

// Okabe-Ito colours, told apart under the common colour-vision deficiencies; cycles after 8.
Rgb palette(std::size_t index);

enum class Mark { Line, Points, LinePoints };
enum class Shape { Circle, Square, Diamond, Triangle };

struct Series {
  std::string label;         // in the legend; empty: not in it
  std::vector<double> x, y;  // same length; NaN, inf (and <= 0 on a log axis) leave a gap
  Mark mark = Mark::Line;
  std::optional<Rgb> colour;  // unset: palette(index of the series in the chart)
  double width = 2.0;         // px, the line
  bool dashed = false;
  Shape shape = Shape::Circle;
  bool filled = true;                     // false: an open marker (white inside)
  double marker_size = 7.0;               // px, across
  std::vector<std::string> point_labels;  // empty, or one per point, drawn beside it
  std::vector<double> y_error;            // empty, or one half-length per point (y units)
};

struct Axis {
  std::string label;
  bool log = false;
  std::optional<double> min, max;  // data units; unset: the data's extent with a margin
};

// A reference line across the plot (the bed's weight per area, Umf, ...), labelled at its end.
struct Line {
  double value = 0.0;  // data units
  std::string label;
  Rgb colour{90, 90, 90};
  bool dashed = true;
  double width = 1.5;  // px
};

struct Chart {
  std::string title;
  Axis x, y;
  std::vector<Series> series;
  std::vector<Line> hlines, vlines;
  bool legend = true;
  bool grid = true;
  bool equal_aspect = false;  // a metre as long in x as in y (trajectories); the plot box shrinks
};

// An RGB picture, (0, 0) at the top left; pixel (i, j) covers [i, i+1) x [j, j+1).
class Image {
 public:
  Image(int width, int height, Rgb background = {255, 255, 255});  // throws std::invalid_argument
  int width() const { return width_; }
  int height() const { return height_; }
  Rgb at(int x, int y) const;                    // throws std::out_of_range outside
  void set(int x, int y, Rgb c);                 // ignored outside
  void blend(int x, int y, Rgb c, float alpha);  // alpha in [0, 1]; ignored outside
  void paste(const Image& src, int x, int y);    // clipped to this image
  const std::vector<std::uint8_t>& pixels() const { return pixels_; }  // RGB rows, top first
  std::vector<std::uint8_t> encode_png() const;
  // Written to a temporary beside it, then renamed. Throws std::runtime_error naming the path.
  void write_png(const std::string& path) const;

 private:
  int width_, height_;
  std::vector<std::uint8_t> pixels_;
};

// Where the font is looked for (render/font_file.hpp): the given assets folder (the program's is
// render::asset_dir()), then the Debian package's copy.
using render::font_search_paths;

// A TrueType font held in memory. Immutable, cheap to copy, safe to share between threads.
class Font {
 public:
  // The first of PATHS that reads as a font; throws std::runtime_error naming every path tried.
  static Font load(const std::vector<std::string>& paths);
  static Font load_default(const std::string& asset_dir) {
    return load(font_search_paths(asset_dir));
  }
  const std::string& path() const;

  struct Data;
  const Data& data() const { return *data_; }

 private:
  explicit Font(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  std::shared_ptr<const Data> data_;
};

// Tick marks of one axis: the algorithm the frames' colour bars use too (render/ticks.hpp).
using render::linear_ticks;
using render::log_ticks;
using render::Ticks;

struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // px, y down
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool contains(double x, double y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// Data to pixel coordinates of one chart.
struct Transform {
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;  // data units, the plot's edges
  bool x_log = false, y_log = false;
  Box plot;
  double px(double x) const;  // continuous px: the pixel is floor(px)
  double py(double y) const;
};

// Where a chart's parts go in an image of a given size (what render draws).
struct Layout {
  double scale = 1.0;  // of sizes given in px, see the top of this file
  Box title;           // empty when there is no title
  Box plot;
  Box legend;  // empty when there is no legend
  Transform map;
  Ticks x_ticks, y_ticks;
};
// Both throw std::invalid_argument for a malformed chart (lengths that differ, an axis whose
// min is not below its max, a non-positive bound on a log axis), naming the chart and series.
// SCALE > 0 sets the size of text and lines (see the top of this file) instead of the image's
// size: panels of different shapes in one figure then read alike.
Layout layout(const Chart& chart, int width, int height, const Font& font, double scale = 0.0);
Image render(const Chart& chart, int width, int height, const Font& font, double scale = 0.0);

// A chart placed in a figure: its box, px from the figure's top left below the title band.
struct Panel {
  Chart chart;
  int x = 0, y = 0, width = 0, height = 0;
};
// Panels where the caller put them, all drawn at SCALE; TITLE (when not empty) in a band above
// them, its size at SCALE too. The figure is as large as its panels reach.
Image render_figure(const std::vector<Panel>& panels, double scale, const Font& font,
                    const std::string& title = "");

// Panels of PANEL_W x PANEL_H, COLUMNS to a row, filled row by row (a figure at the scale of one
// panel); TITLE (when not empty) in a band above them.
Image render_grid(const std::vector<Chart>& charts, int columns, int panel_w, int panel_h,
                  const Font& font, const std::string& title = "");

}  // namespace fluidbed::chart
