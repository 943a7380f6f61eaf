#include "view/bed_labels.hpp"

#include <algorithm>

namespace fluidbed::app {

double bed_surface(const BubbleView& v) {
  const FineGrid& g = v.grid;
  if (g.nx <= 0 || g.ny <= 0 || v.label.size() != static_cast<std::size_t>(g.cells()))
    return g.height();
  int surface = g.ny;
  for (int j = g.ny - 1; j >= 0; --j) {
    int free = 0;
    for (int i = 0; i < g.nx; ++i)
      free += v.label[static_cast<std::size_t>(g.index(i, j))] == kCellFreeboard ? 1 : 0;
    if (free < kFreeboardShare * g.nx) break;
    surface = j;
  }
  return surface * g.dy;
}

std::vector<BedLabel> bed_labels(const Snapshot& s, const BubbleView& v) {
  std::vector<BedLabel> out;
  std::vector<std::size_t> bubbles;
  bool jet = false;
  for (std::size_t k = 0; k < v.regions.size(); ++k) {
    const Bubble& b = v.regions[k];
    if (b.touches_jet) {
      out.push_back({"jet", b.x, b.y});
      jet = true;
    } else if (b.slug) {
      out.push_back({"slug", b.x, b.y});
    } else {
      bubbles.push_back(k);
    }
  }
  std::sort(bubbles.begin(), bubbles.end(),
            [&](std::size_t a, std::size_t b) { return v.regions[a].area > v.regions[b].area; });
  if (bubbles.size() > static_cast<std::size_t>(kMaxBubbleLabels)) bubbles.resize(kMaxBubbleLabels);
  for (std::size_t k : bubbles) out.push_back({"bubble", v.regions[k].x, v.regions[k].y});

  const double height = v.grid.height(), surface = bed_surface(v);
  if (height > 0.0 && height - surface >= kFreeboardRoom * height)
    out.push_back({"freeboard", 0.5 * v.grid.width(), 0.5 * (surface + height)});

  if (jet && s.particles() > 0 && s.vx.size() == s.particles()) {
    double total = 0.0;
    for (std::size_t i = 0; i < s.particles(); ++i) total += s.speed(i);
    const double mean = total / static_cast<double>(s.particles());
    const double w = kCornerShare * s.width, h = std::min(w, surface / 3.0);
    if (mean > kMovingSpeed && h > 0.0) {
      for (const double x0 : {0.0, s.width - w}) {
        double sum = 0.0;
        int n = 0;
        for (std::size_t i = 0; i < s.particles(); ++i)
          if (s.x[i] >= x0 && s.x[i] <= x0 + w && s.y[i] <= h) {
            sum += s.speed(i);
            ++n;
          }
        if (n >= 5 && sum / n < kDeadShare * mean)
          out.push_back({"dead zone", x0 + 0.5 * w, 0.5 * h});
      }
    }
  }
  return out;
}

}  // namespace fluidbed::app
