// Charts: checking one and laying it out (ranges, ticks, margins, legend); drawing is in
// draw.cpp.
#include "chart/chart.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "chart/plan.hpp"

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

using namespace detail;

namespace {

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

}  // namespace

namespace detail {

Plan make_plan(const Chart& c, int width, int height, const TextPainter& text, double scale) {
  check(c);
  Plan plan;
  Layout& out = plan.layout;
  out.scale = scale > 0.0 ? scale : scale_of(width, height);
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

}  // namespace detail

Layout layout(const Chart& chart, int width, int height, const Font& font, double scale) {
  const TextPainter text(font);
  return make_plan(chart, width, height, text, scale).layout;
}

Image render(const Chart& chart, int width, int height, const Font& font, double scale) {
  Image img(width, height);
  TextPainter text(font);
  const Plan plan = make_plan(chart, width, height, text, scale);
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

Image render_figure(const std::vector<Panel>& panels, double scale, const Font& font,
                    const std::string& title) {
  if (panels.empty()) throw std::invalid_argument("a figure needs at least one chart");
  int width = 0, height = 0;
  for (const Panel& p : panels) {
    width = std::max(width, p.x + p.width);
    height = std::max(height, p.y + p.height);
  }
  TextPainter text(font);
  const double title_size = 19 * scale;
  const int band =
      title.empty() ? 0 : static_cast<int>(std::lround(text.height(title_size) + 24 * scale));
  Image img(width, height + band);
  if (!title.empty()) {
    text.draw(img, title, 0.5 * img.width(), 14 * scale, title_size, kInk, Align::Centre,
              Anchor::Top);
  }
  for (const Panel& p : panels)
    img.paste(render(p.chart, p.width, p.height, font, scale), p.x, band + p.y);
  return img;
}

Image render_grid(const std::vector<Chart>& charts, int columns, int panel_w, int panel_h,
                  const Font& font, const std::string& title) {
  if (charts.empty()) throw std::invalid_argument("a figure needs at least one chart");
  if (columns < 1) throw std::invalid_argument("a figure needs at least one column");
  columns = std::min(columns, static_cast<int>(charts.size()));
  std::vector<Panel> panels;
  for (std::size_t k = 0; k < charts.size(); ++k) {
    const int col = static_cast<int>(k) % columns, row = static_cast<int>(k) / columns;
    panels.push_back({charts[k], col * panel_w, row * panel_h, panel_w, panel_h});
  }
  return render_figure(panels, scale_of(panel_w, panel_h), font, title);
}

}  // namespace fluidbed::chart
