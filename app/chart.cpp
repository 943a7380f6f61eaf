// Charts: checking one, laying it out (ranges, ticks, margins, legend) and drawing it.
#include "chart.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "chart_raster.hpp"
#include "chart_text.hpp"

namespace fluidbed::chart {

using detail::Align;
using detail::Anchor;
using detail::Coverage;
using detail::Point;
using detail::TextPainter;

Rgb palette(std::size_t index) {
  // Okabe & Ito (2008), yellow last: it is faint on white.
  static constexpr std::array<Rgb, 8> kColours = {{{0, 114, 178},
                                                   {213, 94, 0},
                                                   {0, 158, 115},
                                                   {204, 121, 167},
                                                   {230, 159, 0},
                                                   {86, 180, 233},
                                                   {0, 0, 0},
                                                   {240, 228, 66}}};
  return kColours[index % kColours.size()];
}

double Transform::px(double x) const {
  const double t = x_log
                       ? (std::log10(x) - std::log10(x_lo)) / (std::log10(x_hi) - std::log10(x_lo))
                       : (x - x_lo) / (x_hi - x_lo);
  return plot.x0 + t * plot.width();
}

double Transform::py(double y) const {
  const double t = y_log
                       ? (std::log10(y) - std::log10(y_lo)) / (std::log10(y_hi) - std::log10(y_lo))
                       : (y - y_lo) / (y_hi - y_lo);
  return plot.y1 - t * plot.height();
}

namespace {

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

double scale_of(int width, int height) {
  return std::max(0.25, std::min(width / 800.0, height / 500.0));
}

bool usable(double v, bool log) {
  return std::isfinite(v) && (!log || v > 0.0);
}

std::string name_of(const Chart& c) {
  return "chart \"" + c.title + "\"";
}

void check_axis(const Chart& c, const Axis& a, const char* which) {
  const std::string where = name_of(c) + ", " + which + " axis: ";
  for (const auto& bound : {a.min, a.max}) {
    if (bound && !std::isfinite(*bound))
      throw std::invalid_argument(where + "a bound is not finite");
    if (bound && a.log && !(*bound > 0.0)) {
      throw std::invalid_argument(where + "a log axis needs bounds above 0, not " +
                                  std::to_string(*bound));
    }
  }
  if (a.min && a.max && !(*a.min < *a.max)) {
    throw std::invalid_argument(where + "min " + std::to_string(*a.min) + " is not below max " +
                                std::to_string(*a.max));
  }
}

void check(const Chart& c) {
  check_axis(c, c.x, "x");
  check_axis(c, c.y, "y");
  for (std::size_t i = 0; i < c.series.size(); ++i) {
    const Series& s = c.series[i];
    const std::string where =
        name_of(c) + ", series " + std::to_string(i) + " \"" + s.label + "\": ";
    const auto count = [](std::size_t n) { return std::to_string(n); };
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument(where + count(s.x.size()) + " x values but " + count(s.y.size()) +
                                  " y values");
    }
    if (!s.point_labels.empty() && s.point_labels.size() != s.x.size()) {
      throw std::invalid_argument(where + count(s.point_labels.size()) + " point labels for " +
                                  count(s.x.size()) + " points");
    }
    if (!s.y_error.empty() && s.y_error.size() != s.x.size()) {
      throw std::invalid_argument(where + count(s.y_error.size()) + " error bars for " +
                                  count(s.x.size()) + " points");
    }
    if (!(s.width >= 0.0) || !(s.marker_size >= 0.0) || !std::isfinite(s.width) ||
        !std::isfinite(s.marker_size)) {
      throw std::invalid_argument(where + "width and marker_size must be finite and >= 0");
    }
  }
}

struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return lo > hi; }
};

// What the data (and the reference lines) span on each axis; only points drawable on both.
void data_extents(const Chart& c, Extent& ex, Extent& ey) {
  for (const Series& s : c.series) {
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (!usable(s.x[k], c.x.log) || !usable(s.y[k], c.y.log)) continue;
      ex.add(s.x[k]);
      ey.add(s.y[k]);
      if (!s.y_error.empty() && std::isfinite(s.y_error[k])) {
        const double e = std::abs(s.y_error[k]);
        if (usable(s.y[k] - e, c.y.log)) ey.add(s.y[k] - e);
        ey.add(s.y[k] + e);
      }
    }
  }
  for (const Line& l : c.vlines) {
    if (usable(l.value, c.x.log)) ex.add(l.value);
  }
  for (const Line& l : c.hlines) {
    if (usable(l.value, c.y.log)) ey.add(l.value);
  }
}

// The span an axis shows: its bounds where set, else the data's with PAD of the span added
// (in decades on a log axis). A single value gets some span around it.
std::pair<double, double> axis_range(const Axis& axis, Extent data, double pad) {
  if (axis.min && axis.max) return {*axis.min, *axis.max};
  const auto to_u = [&axis](double v) { return axis.log ? std::log10(v) : v; };
  const auto from_u = [&axis](double u) { return axis.log ? std::pow(10.0, u) : u; };
  if (data.empty()) {
    data.add(axis.log ? 1.0 : 0.0);
    data.add(axis.log ? 10.0 : 1.0);
  }
  double lo = axis.min ? to_u(*axis.min) : to_u(data.lo);
  double hi = axis.max ? to_u(*axis.max) : to_u(data.hi);
  if (hi > lo) {
    const double span = hi - lo;
    if (!axis.min) lo -= pad * span;
    if (!axis.max) hi += pad * span;
  } else {
    // One value, or data all beyond a lone bound: a span of a decade or a tenth of the value.
    const double c = axis.min ? lo : hi;
    const double d = axis.log ? 0.5 : (c != 0.0 ? 0.1 * std::abs(c) : 1.0);
    if (axis.min) {
      hi = lo + 2 * d;
    } else if (axis.max) {
      lo = hi - 2 * d;
    } else {
      lo = c - d;
      hi = c + d;
    }
  }
  return {from_u(lo), from_u(hi)};
}

// The ticks for SPAN px of axis, no closer than what their labels need side by side (ALONG:
// labels of the x axis lie along it) or a comfortable spacing (the y axis).
Ticks ticks_for(const Axis& axis, double lo, double hi, double span, double spacing, bool along,
                const TextPainter& text, double tick_size) {
  int target = std::max(2, static_cast<int>(std::lround(span / spacing)) + 1);
  Ticks t;
  for (; target >= 2; --target) {
    t = axis.log ? log_ticks(lo, hi, target) : linear_ticks(lo, hi, target);
    if (!along || t.major.size() < 2) break;
    // Each pair of neighbouring labels must fit between their ticks, with a gap.
    const auto u = [&axis](double v) { return axis.log ? std::log10(v) : v; };
    const double per_u = span / (u(hi) - u(lo));
    bool fits = true;
    for (std::size_t k = 1; k < t.major.size(); ++k) {
      const double room = (u(t.major[k]) - u(t.major[k - 1])) * per_u;
      const double need =
          0.5 * (text.width(t.labels[k - 1], tick_size) + text.width(t.labels[k], tick_size)) +
          1.2 * tick_size;
      fits = fits && need <= room;
    }
    if (fits) break;
  }
  return t;
}

// The full plan of a chart: the public layout plus what only drawing needs.
struct Plan {
  Layout layout;
  Sizes z{1.0};
  std::vector<std::size_t> legend_entries;  // series indices
  double legend_row = 0.0;                  // px
};

double snap(double c, double width) {
  // A line of an odd number of px is crisp centred on a pixel, of an even number between two.
  return static_cast<long>(std::lround(width)) % 2 == 1 ? std::floor(c) + 0.5 : std::round(c);
}

std::vector<Point> to_px(const Transform& m, const Series& s, std::size_t k0, std::size_t k1) {
  std::vector<Point> run;
  for (std::size_t k = k0; k < k1; ++k) run.push_back({m.px(s.x[k]), m.py(s.y[k])});
  return run;
}

// Runs of points drawable on both axes: a NaN, an inf or a log of <= 0 ends a run.
template <class F>
void for_each_run(const Chart& c, const Series& s, F f) {
  std::size_t k0 = 0;
  for (std::size_t k = 0; k <= s.x.size(); ++k) {
    const bool ok = k < s.x.size() && usable(s.x[k], c.x.log) && usable(s.y[k], c.y.log);
    if (ok) continue;
    if (k > k0) f(k0, k);
    k0 = k + 1;
  }
}

// Length of segment A-B inside BOX (Liang-Barsky), for choosing where the legend hides least.
double length_inside(Point a, Point b, const Box& box) {
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

double overlap(const Box& a, const Box& b) {
  const double w = std::min(a.x1, b.x1) - std::max(a.x0, b.x0);
  const double h = std::min(a.y1, b.y1) - std::max(a.y0, b.y0);
  return w > 0.0 && h > 0.0 ? w * h : 0.0;
}

// How much of the data a legend at BOX would hide: px of line plus a marker's worth per point.
double hidden_by(const Chart& c, const Transform& m, const Box& box, double scale) {
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

Plan make_plan(const Chart& c, int width, int height, const TextPainter& text) {
  check(c);
  Plan plan;
  Layout& out = plan.layout;
  out.scale = scale_of(width, height);
  const double s = out.scale;
  plan.z = Sizes(s);
  const Sizes& z = plan.z;

  Extent ex, ey;
  data_extents(c, ex, ey);
  bool lines_only = true;  // a line-only x axis runs edge to edge; markers get a margin
  for (const Series& ser : c.series) lines_only = lines_only && ser.mark == Mark::Line;
  const auto [x_lo, x_hi] = axis_range(c.x, ex, lines_only ? 0.0 : 0.05);
  const auto [y_lo, y_hi] = axis_range(c.y, ey, 0.05);
  Transform& m = out.map;
  m = {x_lo, x_hi, y_lo, y_hi, c.x.log, c.y.log, {}};

  const double tick_h = text.height(z.tick);
  // Margins, first without and then with room for the multipliers the first pass found.
  bool x_mult = false, y_mult = false;
  for (int pass = 0; pass < 2; ++pass) {
    double top = z.pad;
    if (!c.title.empty()) {
      out.title = text.bounds(c.title, 0.5 * width, top, z.title, Align::Centre, Anchor::Top);
      top = out.title.y1 + 2.0 * z.gap;
    }
    top += y_mult ? tick_h + 2.0 * z.gap : 0.5 * tick_h;
    double bottom = z.pad + z.frame + z.tick_len + z.gap + tick_h;
    if (!c.x.label.empty()) bottom += 1.5 * z.gap + text.height(z.label);
    if (x_mult && c.x.label.empty()) bottom += 1.5 * z.gap + tick_h;
    const double y0 = std::round(top), y1 = std::round(height - bottom);

    out.y_ticks = ticks_for(c.y, y_lo, y_hi, y1 - y0, 55 * s, false, text, z.tick);
    double widest = 0.0;
    for (const std::string& l : out.y_ticks.labels)
      widest = std::max(widest, text.width(l, z.tick));
    double left = z.pad + widest + z.gap + z.tick_len + z.frame;
    if (!c.y.label.empty()) left += text.height(z.label) + 2.0 * z.gap;
    const double x0 = std::round(left);
    double right = z.pad + z.frame;
    for (int fit = 0; fit < 2; ++fit) {
      const double x1 = std::round(width - right);
      m.plot = {x0, y0, x1, y1};
      out.x_ticks = ticks_for(c.x, x_lo, x_hi, x1 - x0, 90 * s, true, text, z.tick);
      if (out.x_ticks.major.empty()) break;
      // The last label may hang past the plot's right edge; make room for it.
      const double hang =
          m.px(out.x_ticks.major.back()) + 0.5 * text.width(out.x_ticks.labels.back(), z.tick) - x1;
      if (hang <= 0.0) break;
      right += hang;
    }
    const bool x_now = !out.x_ticks.multiplier.empty(), y_now = !out.y_ticks.multiplier.empty();
    if (x_now == x_mult && y_now == y_mult) break;
    x_mult = x_now;
    y_mult = y_now;
  }

  // One metre as long in x as in y: the plot box shrinks about its centre.
  if (c.equal_aspect && !c.x.log && !c.y.log) {
    Box& p = m.plot;
    const double per_x = p.width() / (x_hi - x_lo), per_y = p.height() / (y_hi - y_lo);
    if (per_x > per_y) {
      const double w = std::round(per_y * (x_hi - x_lo));
      p.x0 = std::round(0.5 * (p.x0 + p.x1 - w));
      p.x1 = p.x0 + w;
    } else {
      const double h = std::round(per_x * (y_hi - y_lo));
      p.y0 = std::round(0.5 * (p.y0 + p.y1 - h));
      p.y1 = p.y0 + h;
    }
    out.x_ticks = ticks_for(c.x, x_lo, x_hi, p.width(), 90 * s, true, text, z.tick);
    out.y_ticks = ticks_for(c.y, y_lo, y_hi, p.height(), 55 * s, false, text, z.tick);
  }
  // An image too small for its margins still gets a plot box of a pixel.
  m.plot.x1 = std::max(m.plot.x1, m.plot.x0 + 1.0);
  m.plot.y1 = std::max(m.plot.y1, m.plot.y0 + 1.0);
  out.plot = m.plot;
  if (!c.title.empty()) {
    // Centred over the plot when it fits there, else over the image.
    const double tw = text.width(c.title, z.title);
    const double cx = tw <= out.plot.width() ? 0.5 * (out.plot.x0 + out.plot.x1) : 0.5 * width;
    out.title = text.bounds(c.title, cx, z.pad, z.title, Align::Centre, Anchor::Top);
  }

  // The legend in the corner of the plot where it hides the least data.
  for (std::size_t i = 0; i < c.series.size(); ++i) {
    if (!c.series[i].label.empty()) plan.legend_entries.push_back(i);
  }
  if (c.legend && !plan.legend_entries.empty()) {
    plan.legend_row = 1.45 * z.legend;
    double widest = 0.0;
    for (std::size_t i : plan.legend_entries) {
      widest = std::max(widest, text.width(c.series[i].label, z.legend));
    }
    const double w = 2 * z.pad * 0.7 + 26 * s + 1.5 * z.gap + widest;
    const double h = plan.legend_row * static_cast<double>(plan.legend_entries.size()) + 2 * z.gap;
    const double inset = 8 * s;
    const Box& p = out.plot;
    const std::array<Box, 4> corners = {
        {{p.x1 - inset - w, p.y0 + inset, p.x1 - inset, p.y0 + inset + h},
         {p.x0 + inset, p.y0 + inset, p.x0 + inset + w, p.y0 + inset + h},
         {p.x1 - inset - w, p.y1 - inset - h, p.x1 - inset, p.y1 - inset},
         {p.x0 + inset, p.y1 - inset - h, p.x0 + inset + w, p.y1 - inset}}};
    double least = std::numeric_limits<double>::infinity();
    for (const Box& b : corners) {
      const double hidden = hidden_by(c, m, b, s);
      if (hidden < least) {
        least = hidden;
        out.legend = {std::round(b.x0), std::round(b.y0), std::round(b.x1), std::round(b.y1)};
      }
    }
  }
  return plan;
}

void draw_marker_series(Coverage& cov, Image& img, const Series& s, const std::vector<Point>& pts,
                        Rgb colour, double scale) {
  const double size = s.marker_size * scale;
  if (!s.filled) {
    for (const Point& p : pts) cov.marker(p, size, s.shape);
    cov.composite(img, kWhite);
  }
  const double ring = s.filled ? 0.0 : std::max(1.2, 1.5 * scale);
  for (const Point& p : pts) cov.marker(p, size, s.shape, ring);
  cov.composite(img, colour);
}

// A faint white box under text that lies over data, so that it reads.
void backdrop(Coverage& cov, Image& img, const Box& b, double pad) {
  cov.rect({b.x0 - pad, b.y0 - pad, b.x1 + pad, b.y1 + pad});
  cov.composite(img, kWhite, 0.85F);
}

void draw_point_labels(const Chart& c, const Plan& plan, Image& img, Coverage& cov,
                       TextPainter& text) {
  const Transform& m = plan.layout.map;
  const Sizes& z = plan.z;
  const double s = plan.layout.scale;
  // What a label should not cover: the legend, every marker, the labels placed before it.
  std::vector<Box> taken;
  if (plan.layout.legend.width() > 0.0) taken.push_back(plan.layout.legend);
  for (const Series& ser : c.series) {
    if (ser.mark == Mark::Line) continue;
    const double r = 0.5 * ser.marker_size * s + 1.0;
    for_each_run(c, ser, [&](std::size_t k0, std::size_t k1) {
      for (std::size_t k = k0; k < k1; ++k) {
        const double x = m.px(ser.x[k]), y = m.py(ser.y[k]);
        taken.push_back({x - r, y - r, x + r, y + r});
      }
    });
  }
  // And the lines: the series' segments and the reference lines.
  std::vector<std::pair<Point, Point>> segments;
  for (const Series& ser : c.series) {
    if (ser.mark == Mark::Points) continue;
    for_each_run(c, ser, [&](std::size_t k0, std::size_t k1) {
      for (std::size_t k = k0 + 1; k < k1; ++k) {
        segments.push_back(
            {{m.px(ser.x[k - 1]), m.py(ser.y[k - 1])}, {m.px(ser.x[k]), m.py(ser.y[k])}});
      }
    });
  }
  const Box& p = plan.layout.plot;
  for (const Line& l : c.hlines) segments.push_back({{p.x0, m.py(l.value)}, {p.x1, m.py(l.value)}});
  for (const Line& l : c.vlines) segments.push_back({{m.px(l.value), p.y0}, {m.px(l.value), p.y1}});
  constexpr std::size_t kMaxAvoided = 4000;  // beyond this, labels just go to the right
  for (const Series& ser : c.series) {
    if (ser.point_labels.empty()) continue;
    const double g = 0.5 * ser.marker_size * s + 3 * s, d = 0.75 * g;
    for_each_run(c, ser, [&](std::size_t k0, std::size_t k1) {
      for (std::size_t k = k0; k < k1; ++k) {
        const std::string& label = ser.point_labels[k];
        if (label.empty()) continue;
        const double x = m.px(ser.x[k]), y = m.py(ser.y[k]);
        if (!plan.layout.plot.contains(x, y)) continue;
        struct Spot {
          double x, y;
          Align align;
          Anchor anchor;
        };
        const std::array<Spot, 8> spots = {{{x + g, y, Align::Start, Anchor::Middle},
                                            {x + d, y - d, Align::Start, Anchor::Bottom},
                                            {x + d, y + d, Align::Start, Anchor::Top},
                                            {x - g, y, Align::End, Anchor::Middle},
                                            {x, y - g, Align::Centre, Anchor::Bottom},
                                            {x, y + g, Align::Centre, Anchor::Top},
                                            {x - d, y - d, Align::End, Anchor::Bottom},
                                            {x - d, y + d, Align::End, Anchor::Top}}};
        const Spot* best = &spots[0];
        double best_cost = std::numeric_limits<double>::infinity();
        for (const Spot& spot : spots) {
          const Box b = text.bounds(label, spot.x, spot.y, z.point_label, spot.align, spot.anchor);
          double cost = 4.0 * (b.width() * b.height() - overlap(b, p));  // outside the plot
          if (taken.size() <= kMaxAvoided) {
            for (const Box& t : taken) cost += overlap(b, t);
          }
          if (segments.size() <= kMaxAvoided) {
            // A line through a label costs like a strip of it as tall as the text.
            for (const auto& [a0, a1] : segments) cost += b.height() * length_inside(a0, a1, b);
          }
          if (cost < best_cost) {
            best_cost = cost;
            best = &spot;
          }
          if (cost == 0.0) break;
        }
        const Box b =
            text.bounds(label, best->x, best->y, z.point_label, best->align, best->anchor);
        backdrop(cov, img, b, 1.0 * s);
        text.draw(img, label, best->x, best->y, z.point_label, kSoftInk, best->align, best->anchor);
        taken.push_back(b);
      }
    });
  }
}

// The lines go under the data (LABELS false), their labels over it (LABELS true).
void draw_reference_lines(const Chart& c, const Plan& plan, Image& img, Coverage& cov,
                          TextPainter& text, bool labels) {
  const Transform& m = plan.layout.map;
  const Box& p = plan.layout.plot;
  const double s = plan.layout.scale;
  const Sizes& z = plan.z;
  const auto draw = [&](const Line& l, bool horizontal) {
    if (!usable(l.value, horizontal ? c.y.log : c.x.log)) return;
    const double w = std::max(1.0, std::round(l.width * s));
    const double v = snap(horizontal ? m.py(l.value) : m.px(l.value), w);
    if (horizontal ? (v < p.y0 || v > p.y1) : (v < p.x0 || v > p.x1)) return;
    const Point a = horizontal ? Point{p.x0, v} : Point{v, p.y0};
    const Point b = horizontal ? Point{p.x1, v} : Point{v, p.y1};
    // Butt-ended lines: a thin rectangle when solid, dashes of a rectangle each when dashed.
    if (!labels) {
      const double len = horizontal ? p.width() : p.height();
      const double dash = l.dashed ? 7 * s : len, gap = l.dashed ? 4 * s : 0.0;
      for (double t = 0.0; t < len; t += dash + gap) {
        const double t1 = std::min(len, t + dash);
        cov.rect(horizontal ? Box{a.x + t, v - 0.5 * w, a.x + t1, v + 0.5 * w}
                            : Box{v - 0.5 * w, b.y - t1, v + 0.5 * w, b.y - t});
      }
      cov.composite(img, l.colour);
      return;
    }
    if (l.label.empty()) return;
    // At an end of the line, on the side where the label hides the least data and the legend.
    struct Spot {
      double x, y;
      Align align;
      Anchor anchor;
    };
    const double inset = 2 * z.gap;
    const std::array<Spot, 4> spots =
        horizontal ? std::array<Spot, 4>{{{p.x1 - inset, v - z.gap, Align::End, Anchor::Bottom},
                                          {p.x1 - inset, v + z.gap, Align::End, Anchor::Top},
                                          {p.x0 + inset, v - z.gap, Align::Start, Anchor::Bottom},
                                          {p.x0 + inset, v + z.gap, Align::Start, Anchor::Top}}}
                   : std::array<Spot, 4>{{{v + z.gap, p.y0 + inset, Align::Start, Anchor::Top},
                                          {v - z.gap, p.y0 + inset, Align::End, Anchor::Top},
                                          {v + z.gap, p.y1 - inset, Align::Start, Anchor::Bottom},
                                          {v - z.gap, p.y1 - inset, Align::End, Anchor::Bottom}}};
    const Spot* best = &spots[0];
    double least = std::numeric_limits<double>::infinity();
    for (const Spot& spot : spots) {
      const Box at = text.bounds(l.label, spot.x, spot.y, z.tick, spot.align, spot.anchor);
      const double outside = at.width() * at.height() - overlap(at, p);
      const double hidden =
          50.0 * outside + hidden_by(c, m, at, s) + overlap(at, plan.layout.legend);
      if (hidden < least) {
        least = hidden;
        best = &spot;
      }
    }
    cov.reset_clip();
    const Box box = text.bounds(l.label, best->x, best->y, z.tick, best->align, best->anchor);
    backdrop(cov, img, box, 1.0 * s);
    text.draw(img, l.label, best->x, best->y, z.tick, l.colour, best->align, best->anchor);
    cov.set_clip(p);
  };
  cov.set_clip(p);
  for (const Line& l : c.hlines) draw(l, true);
  for (const Line& l : c.vlines) draw(l, false);
  cov.reset_clip();
}

void draw_series(const Chart& c, const Plan& plan, Image& img, Coverage& cov) {
  const Transform& m = plan.layout.map;
  const double s = plan.layout.scale;
  cov.set_clip(plan.layout.plot);
  for (std::size_t i = 0; i < c.series.size(); ++i) {
    const Series& ser = c.series[i];
    const Rgb colour = ser.colour.value_or(palette(i));
    if (ser.mark != Mark::Points) {
      for_each_run(c, ser, [&](std::size_t k0, std::size_t k1) {
        const double dash = ser.dashed ? 6 * s : 0.0, gap = ser.dashed ? 4 * s : 0.0;
        cov.polyline(to_px(m, ser, k0, k1), ser.width * s, dash, gap);
      });
      cov.composite(img, colour);
    }
    if (!ser.y_error.empty()) {
      const double cap = 0.5 * std::max(ser.marker_size, 4.0) * s;
      for_each_run(c, ser, [&](std::size_t k0, std::size_t k1) {
        for (std::size_t k = k0; k < k1; ++k) {
          const double e = std::abs(ser.y_error[k]);
          if (!std::isfinite(e) || e == 0.0) continue;
          const double x = m.px(ser.x[k]);
          const double lo =
              usable(ser.y[k] - e, c.y.log) ? m.py(ser.y[k] - e) : plan.layout.plot.y1;
          const double hi = m.py(ser.y[k] + e);
          const double w = 1.2 * s;
          cov.segment({x, lo}, {x, hi}, w);
          cov.segment({x - cap, lo}, {x + cap, lo}, w);
          cov.segment({x - cap, hi}, {x + cap, hi}, w);
        }
      });
      cov.composite(img, colour);
    }
    if (ser.mark != Mark::Line) {
      std::vector<Point> pts;
      for_each_run(c, ser, [&](std::size_t k0, std::size_t k1) {
        const std::vector<Point> run = to_px(m, ser, k0, k1);
        pts.insert(pts.end(), run.begin(), run.end());
      });
      draw_marker_series(cov, img, ser, pts, colour, s);
    }
  }
  cov.reset_clip();
}

void draw_axes(const Chart& c, const Plan& plan, Image& img, Coverage& cov, TextPainter& text) {
  const Layout& out = plan.layout;
  const Transform& m = out.map;
  const Box& p = out.plot;
  const Sizes& z = plan.z;
  const double f = z.frame;
  // The frame, just outside the plot box so that it hides no data.
  cov.rect({p.x0 - f, p.y0 - f, p.x1 + f, p.y0});
  cov.rect({p.x0 - f, p.y1, p.x1 + f, p.y1 + f});
  cov.rect({p.x0 - f, p.y0, p.x0, p.y1});
  cov.rect({p.x1, p.y0, p.x1 + f, p.y1});
  // Ticks pointing out.
  const auto x_tick = [&](double v, double len) {
    const double x = snap(m.px(v), f);
    if (x < p.x0 - 0.5 || x > p.x1 + 0.5) return false;
    cov.rect({x - 0.5 * f, p.y1 + f, x + 0.5 * f, p.y1 + f + len});
    return true;
  };
  const auto y_tick = [&](double v, double len) {
    const double y = snap(m.py(v), f);
    if (y < p.y0 - 0.5 || y > p.y1 + 0.5) return false;
    cov.rect({p.x0 - f - len, y - 0.5 * f, p.x0 - f, y + 0.5 * f});
    return true;
  };
  for (double v : out.x_ticks.minor) x_tick(v, z.minor_len);
  for (double v : out.y_ticks.minor) y_tick(v, z.minor_len);
  for (double v : out.x_ticks.major) x_tick(v, z.tick_len);
  for (double v : out.y_ticks.major) y_tick(v, z.tick_len);
  cov.composite(img, kInk);

  const double label_top = p.y1 + f + z.tick_len + z.gap;
  for (std::size_t k = 0; k < out.x_ticks.major.size(); ++k) {
    text.draw(img, out.x_ticks.labels[k], m.px(out.x_ticks.major[k]), label_top, z.tick, kInk,
              Align::Centre, Anchor::Top);
  }
  const double label_right = p.x0 - f - z.tick_len - z.gap;
  for (std::size_t k = 0; k < out.y_ticks.major.size(); ++k) {
    text.draw(img, out.y_ticks.labels[k], label_right, m.py(out.y_ticks.major[k]), z.tick, kInk,
              Align::End, Anchor::Middle);
  }
  const double tick_h = text.height(z.tick);
  if (!out.y_ticks.multiplier.empty()) {
    text.draw(img, out.y_ticks.multiplier, p.x0, p.y0 - 2 * z.gap, z.tick, kInk, Align::Start,
              Anchor::Bottom);
  }
  const double row = label_top + tick_h + 1.5 * z.gap;  // below the x tick labels
  if (!out.x_ticks.multiplier.empty()) {
    text.draw(img, out.x_ticks.multiplier, p.x1, row, z.tick, kInk, Align::End, Anchor::Top);
  }
  if (!c.x.label.empty()) {
    text.draw(img, c.x.label, 0.5 * (p.x0 + p.x1), row, z.label, kInk, Align::Centre, Anchor::Top);
  }
  if (!c.y.label.empty()) {
    double widest = 0.0;
    for (const std::string& l : out.y_ticks.labels)
      widest = std::max(widest, text.width(l, z.tick));
    const double x = label_right - widest - 2 * z.gap - text.height(z.label);
    text.draw(img, c.y.label, std::max(x, 0.5 * z.pad), 0.5 * (p.y0 + p.y1), z.label, kInk,
              Align::Centre, Anchor::Top, true);
  }
  if (!c.title.empty()) {
    // The anchor the layout measured the title's box from.
    text.draw(img, c.title, 0.5 * (out.title.x0 + out.title.x1), z.pad, z.title, kInk,
              Align::Centre, Anchor::Top);
  }
}

void draw_grid(const Plan& plan, Image& img, Coverage& cov) {
  const Layout& out = plan.layout;
  const Box& p = out.plot;
  const double w = plan.z.frame;
  for (double v : out.x_ticks.major) {
    const double x = snap(out.map.px(v), w);
    if (x > p.x0 + 0.5 && x < p.x1 - 0.5) cov.rect({x - 0.5 * w, p.y0, x + 0.5 * w, p.y1});
  }
  for (double v : out.y_ticks.major) {
    const double y = snap(out.map.py(v), w);
    if (y > p.y0 + 0.5 && y < p.y1 - 0.5) cov.rect({p.x0, y - 0.5 * w, p.x1, y + 0.5 * w});
  }
  cov.composite(img, kGrid);
}

void draw_legend(const Chart& c, const Plan& plan, Image& img, Coverage& cov, TextPainter& text) {
  const Box& b = plan.layout.legend;
  if (!(b.width() > 0.0)) return;
  const Sizes& z = plan.z;
  const double s = plan.layout.scale;
  cov.rect(b);
  cov.composite(img, kWhite, 0.88F);
  cov.rect({b.x0, b.y0, b.x1, b.y0 + 1});
  cov.rect({b.x0, b.y1 - 1, b.x1, b.y1});
  cov.rect({b.x0, b.y0 + 1, b.x0 + 1, b.y1 - 1});
  cov.rect({b.x1 - 1, b.y0 + 1, b.x1, b.y1 - 1});
  cov.composite(img, kLegendEdge);
  double y = b.y0 + z.gap + 0.5 * plan.legend_row;
  for (std::size_t i : plan.legend_entries) {
    const Series& ser = c.series[i];
    const Rgb colour = ser.colour.value_or(palette(i));
    const double x0 = b.x0 + 0.7 * z.pad, x1 = x0 + 26 * s;
    const double yc = std::floor(y) + 0.5;
    if (ser.mark != Mark::Points) {
      cov.polyline({{x0, yc}, {x1, yc}}, ser.width * s, ser.dashed ? 6 * s : 0.0,
                   ser.dashed ? 4 * s : 0.0);
      cov.composite(img, colour);
    }
    if (ser.mark != Mark::Line)
      draw_marker_series(cov, img, ser, {{0.5 * (x0 + x1), yc}}, colour, s);
    text.draw(img, ser.label, x1 + 1.5 * z.gap, yc, z.legend, kInk, Align::Start, Anchor::Middle);
    y += plan.legend_row;
  }
}

}  // namespace

Layout layout(const Chart& chart, int width, int height, const Font& font) {
  const TextPainter text(font);
  return make_plan(chart, width, height, text).layout;
}

Image render(const Chart& chart, int width, int height, const Font& font) {
  Image img(width, height);
  TextPainter text(font);
  const Plan plan = make_plan(chart, width, height, text);
  Coverage cov(width, height);
  cov.set_clip(plan.layout.plot);
  if (chart.grid) draw_grid(plan, img, cov);
  cov.reset_clip();
  draw_reference_lines(chart, plan, img, cov, text, false);
  draw_series(chart, plan, img, cov);
  draw_reference_lines(chart, plan, img, cov, text, true);
  draw_axes(chart, plan, img, cov, text);
  draw_point_labels(chart, plan, img, cov, text);
  draw_legend(chart, plan, img, cov, text);
  return img;
}

Image render_grid(const std::vector<Chart>& charts, int columns, int panel_w, int panel_h,
                  const Font& font, const std::string& title) {
  if (charts.empty()) throw std::invalid_argument("a figure needs at least one chart");
  if (columns < 1) throw std::invalid_argument("a figure needs at least one column");
  columns = std::min(columns, static_cast<int>(charts.size()));
  const int rows = (static_cast<int>(charts.size()) + columns - 1) / columns;
  const double s = scale_of(panel_w, panel_h);
  TextPainter text(font);
  const double title_size = 19 * s;
  const int band =
      title.empty() ? 0 : static_cast<int>(std::lround(text.height(title_size) + 24 * s));
  Image img(columns * panel_w, rows * panel_h + band);
  if (!title.empty()) {
    text.draw(img, title, 0.5 * img.width(), 14 * s, title_size, kInk, Align::Centre, Anchor::Top);
  }
  for (std::size_t k = 0; k < charts.size(); ++k) {
    const int col = static_cast<int>(k) % columns, row = static_cast<int>(k) / columns;
    img.paste(render(charts[k], panel_w, panel_h, font), col * panel_w, band + row * panel_h);
  }
  return img;
}

}  // namespace fluidbed::chart
