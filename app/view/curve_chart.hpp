#pragma once
// The live Fig. 6 as a chart (chart/chart.hpp): the panel's Save PNG, and the headless lesson
// videos beside the bed. The same picture as `sweep`'s sweep.png: the branches, the bed's weight
// per area, U_mf where the decreasing branch shows it.
#include <string>

#include "chart/chart.hpp"
#include "view/live_curve.hpp"

namespace fluidbed::app {

// u_max (m/s): the velocity axis' end (0: the data's).
chart::Chart curve_chart(const CurveState& c, double u_max = 0.0);
// The chart drawn (1200 x 750 px) with the font file `font`.
chart::Image curve_image(const CurveState& c, const std::string& font, double u_max = 0.0);
// The curve saved to `path`: that chart for a .png, else the points as CSV (write_curve_csv,
// written atomically). Throws when it cannot write.
void write_curve_file(const std::string& path, const CurveState& c, const std::string& font);

}  // namespace fluidbed::app
