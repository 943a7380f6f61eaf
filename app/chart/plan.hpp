#pragma once
// Internal to the chart library: what laying out a chart (chart.cpp) and drawing it
// (draw.cpp) share - colours, sizes, the plan of a chart and small geometry helpers.
#include <algorithm>
#include <cmath>
#include <vector>

#include "chart/chart.hpp"
#include "chart/raster.hpp"
#include "chart/text.hpp"

namespace fluidbed::chart::detail {

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kInk{30, 30, 30};
constexpr Rgb kSoftInk{60, 60, 60};
constexpr Rgb kGrid{226, 226, 226};
constexpr Rgb kLegendEdge{190, 190, 190};

// Sizes in px of one chart at its scale.
struct Sizes {
  explicit Sizes(double s)
      : pad(12 * s),
        gap(4 * s),
        title(17 * s),
        label(14.5 * s),
        tick(12.5 * s),
        legend(12.5 * s),
        point_label(11.5 * s),
        tick_len(5 * s),
        minor_len(3 * s),
        frame(std::max(1.0, std::round(s))) {}
  double pad, gap, title, label, tick, legend, point_label, tick_len, minor_len, frame;
};

inline double scale_of(int width, int height) {
  return std::max(0.25, std::min(width / 800.0, height / 500.0));
}

inline bool usable(double v, bool log) {
  return std::isfinite(v) && (!log || v > 0.0);
}

// The full plan of a chart: the public layout plus what only drawing needs.
struct Plan {
  Layout layout;
  Sizes z{1.0};
  std::vector<std::size_t> legend_entries;  // series indices
  double legend_row = 0.0;                  // px
};

inline double snap(double c, double width) {
  // A line of an odd number of px is crisp centred on a pixel, of an even number between two.
  return static_cast<long>(std::lround(width)) % 2 == 1 ? std::floor(c) + 0.5 : std::round(c);
}

inline std::vector<Point> to_px(const Transform& m, const Series& s, std::size_t k0,
                                std::size_t k1) {
  std::vector<Point> run;
  for (std::size_t k = k0; k < k1; ++k) run.push_back({m.px(s.x[k]), m.py(s.y[k])});
  return run;
}

// Runs of points drawable on both axes: a NaN, an inf or a log of <= 0 ends a run.
template <class F>
inline void for_each_run(const Chart& c, const Series& s, F f) {
  std::size_t k0 = 0;
  for (std::size_t k = 0; k <= s.x.size(); ++k) {
    const bool ok = k < s.x.size() && usable(s.x[k], c.x.log) && usable(s.y[k], c.y.log);
    if (ok) continue;
    if (k > k0) f(k0, k);
    k0 = k + 1;
  }
}

// Length of segment A-B inside BOX (Liang-Barsky), for choosing where the legend hides least.
inline double length_inside(Point a, Point b, const Box& box) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - box.x0, box.x1 - a.x, a.y - box.y0, box.y1 - a.y};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return 0.0;
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0.0) t0 = std::max(t0, t);
    if (p[k] > 0.0) t1 = std::min(t1, t);
    if (t0 > t1) return 0.0;
  }
  return (t1 - t0) * std::hypot(dx, dy);
}

inline double overlap(const Box& a, const Box& b) {
  const double w = std::min(a.x1, b.x1) - std::max(a.x0, b.x0);
  const double h = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
  return w > 0.0 && h > 0.0 ? w * h : 0.0;
}

// How much of the data a legend at BOX would hide: px of line plus a marker's worth per point.
inline double hidden_by(const Chart& c, const Transform& m, const Box& box, double scale) {
  double hidden = 0.0;
  for (const Series& s : c.series) {
    for_each_run(c, s, [&](std::size_t k0, std::size_t k1) {
      for (std::size_t k = k0; k < k1; ++k) {
        const Point p{m.px(s.x[k]), m.py(s.y[k])};
        if (s.mark != Mark::Line && box.contains(p.x, p.y)) hidden += s.marker_size * scale;
        if (s.mark != Mark::Points && k > k0) {
          hidden += length_inside({m.px(s.x[k - 1]), m.py(s.y[k - 1])}, p, box);
        }
      }
    });
  }
  return hidden;
}

// SCALE <= 0: scale_of(width, height).
Plan make_plan(const Chart& c, int width, int height, const TextPainter& text, double scale);

// Drawing, in the order render() calls them (draw.cpp).
void draw_grid(const Plan& plan, Image& img, Coverage& cov);
void draw_reference_lines(const Chart& c, const Plan& plan, Image& img, Coverage& cov,
                          TextPainter& text, bool labels);
void draw_series(const Chart& c, const Plan& plan, Image& img, Coverage& cov);
void draw_axes(const Chart& c, const Plan& plan, Image& img, Coverage& cov, TextPainter& text);
void draw_point_labels(const Chart& c, const Plan& plan, Image& img, Coverage& cov,
                       TextPainter& text);
void draw_legend(const Chart& c, const Plan& plan, Image& img, Coverage& cov, TextPainter& text);

}  // namespace fluidbed::chart::detail
