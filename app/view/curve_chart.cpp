#include "view/curve_chart.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.hpp"

namespace fluidbed::app {

chart::Chart curve_chart(const CurveState& c, double u_max) {
  chart::Chart ch;
  ch.title = "Pressure drop against gas velocity, as the class built it (Fig. 6)";
  ch.x.label = "superficial gas velocity U (m/s)";
  ch.y.label = "mean bed pressure drop (Pa)";
  ch.x.min = 0.0;
  if (u_max > 0.0) ch.x.max = u_max;
  ch.y.min = 0.0;
  double top = 1.2 * c.weight_per_area;
  bool labelled_up = false, labelled_down = false;
  for (const CurveBranch& b : c.branches) {
    chart::Series s;
    s.mark = chart::Mark::LinePoints;
    s.colour = b.increasing ? chart::palette(0) : chart::palette(1);
    if (!b.increasing) {
      s.dashed = true;
      s.filled = false;
      s.shape = chart::Shape::Square;
    }
    // One legend entry per direction.
    bool& labelled = b.increasing ? labelled_up : labelled_down;
    if (!labelled) s.label = b.increasing ? "increasing U" : "decreasing U";
    labelled = true;
    for (const CurvePoint& p : b.points) {
      s.x.push_back(p.u);
      s.y.push_back(p.dp_mean);
      s.y_error.push_back(p.dp_std);
      top = std::max(top, 1.1 * (p.dp_mean + p.dp_std));
    }
    if (!s.x.empty()) ch.series.push_back(std::move(s));
  }
  ch.y.max = top;
  if (ch.series.empty()) {  // an empty chart still needs its axes
    chart::Series none;
    none.mark = chart::Mark::Points;
    none.x = {0.0};
    none.y = {0.0};
    none.marker_size = 0.0;
    ch.series.push_back(none);
    if (!ch.x.max) ch.x.max = 1.0;
  }
  ch.hlines.push_back({c.weight_per_area, "bed weight / area", {90, 90, 90}, true, 1.5});
  if (c.umf.ok) {
    char label[64];
    std::snprintf(label, sizeof label, "U_mf of this curve, rough: %.2f m/s", c.umf.umf);
    ch.vlines.push_back({c.umf.umf, label, chart::palette(1), true, 1.5});
  }
  return ch;
}

chart::Image curve_image(const CurveState& c, const std::string& font, double u_max) {
  return chart::render(curve_chart(c, u_max), 1200, 750, chart::Font::load({font}));
}

void write_curve_file(const std::string& path, const CurveState& c, const std::string& font) {
  if (std::filesystem::path(path).extension() == ".png")
    curve_image(c, font).write_png(path);
  else
    write_file_atomically(path, [&](std::ofstream& out) { write_curve_csv(out, c); });
}

}  // namespace fluidbed::app
