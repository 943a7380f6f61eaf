#pragma once
// Tick marks of an axis: 1-2-5 steps on linear axes, decades on log axes, with labels that use
// a true minus sign and a shared power of ten ("×10⁻⁴") where plain decimals would be long.
// One algorithm for the charts (app/chart) and the frames' colour bars (renderer.cpp). No GL.
#include <string>
#include <vector>

namespace fluidbed::render {

struct Ticks {
  std::vector<double> major, minor;  // data units, ascending
  std::vector<std::string> labels;   // one per major tick (UTF-8)
  std::string multiplier;  // e.g. "×10⁻⁴": the labels read value / 10⁻⁴; empty if none
};
// Steps of 1, 2 or 5 x 10^k inside [lo, hi], about TARGET of them (at least 2 when possible).
Ticks linear_ticks(double lo, double hi, int target);
// Decades inside [lo, hi] (0 < lo < hi), at most MAX_MAJOR of them (every 2nd, 3rd, ... decade
// when more), minor ticks at 2..9 x 10^k; 1-2-5 ticks when fewer than two decades are inside.
Ticks log_ticks(double lo, double hi, int max_major);

}  // namespace fluidbed::render
