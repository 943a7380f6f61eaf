#include "view/panel_layout.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed::app {

PanelLayout panel_layout(int window_width, int window_height) {
  PanelLayout p;
  // By the height, as a 16:9 window of this width would have it at most: a squarer window (1400 x
  // 900) gave the panel a height's text and width, and the beds, limited by the width, shrank.
  const float wanted =
      std::min(static_cast<float>(window_height) / 36.0f, static_cast<float>(window_width) / 64.0f);
  for (float f : kPanelFontSizes)
    if (f <= wanted && f <= kPanelFontMax) p.font = f;
  p.width = std::round(std::min(25.0f * p.font, 0.45f * static_cast<float>(window_width)));
  return p;
}

PresenterLayout presenter_layout(int window_width, int window_height) {
  PresenterLayout p;
  const float wanted = static_cast<float>(window_height) / 28.0f;
  p.font = kPanelFontSizes[0];
  for (float f : kPanelFontSizes)
    if (f <= wanted) p.font = f;
  p.bed_right = std::round(0.30f * static_cast<float>(window_width));
  return p;
}

std::pair<double, double> robust_range(std::vector<float> values, double q, double margin) {
  values.erase(
      std::remove_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }),
      values.end());
  if (values.empty()) return {0.0, 1.0};
  const auto at = [&](double share) {
    const auto k =
        static_cast<std::size_t>(std::lround(share * static_cast<double>(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return static_cast<double>(values[k]);
  };
  const double lo = at(q), hi = at(1.0 - q);
  const double span = hi - lo;
  if (!(span > 0.0)) {
    const double pad = std::max(1e-12, 0.01 * std::fabs(lo));
    return {lo - pad, hi + pad};
  }
  return {lo - margin * span, hi + margin * span};
}

}  // namespace fluidbed::app
