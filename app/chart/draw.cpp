// Charts: drawing a planned chart - grid, reference lines, series, axes, labels, legend.
// Split from chart.cpp, which checks and lays out a chart.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "chart/plan.hpp"

namespace fluidbed::chart::detail {

static void draw_marker_series(Coverage& cov, Image& img, const Series& s,
                               const std::vector<Point>& pts, Rgb colour, double scale) {
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
static void backdrop(Coverage& cov, Image& img, const Box& b, double pad) {
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

}  // namespace fluidbed::chart::detail
