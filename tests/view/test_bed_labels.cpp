// The presenter mode's words in the bed (view/bed_labels.hpp) on a made-up analysis of the
// paper's box: each rule names what it finds, where it is, and nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "view/bed_labels.hpp"

using namespace fluidbed;
using namespace fluidbed::app;

namespace {

// The paper's box on a 1 cm fine grid: dense to 0.4 m, freeboard above.
BubbleView analysed_box(double surface = 0.4) {
  BubbleView v;
  v.grid.nx = 15;
  v.grid.ny = 90;
  v.grid.dx = v.grid.dy = 0.01;
  v.label.assign(static_cast<std::size_t>(v.grid.cells()), kCellDense);
  for (int j = 0; j < v.grid.ny; ++j)
    for (int i = 0; i < v.grid.nx; ++i)
      if ((j + 0.5) * v.grid.dy > surface)
        v.label[static_cast<std::size_t>(v.grid.index(i, j))] = kCellFreeboard;
  return v;
}

Bubble region(double x, double y, double area, bool jet = false, bool slug = false) {
  Bubble b;
  b.x = x;
  b.y = y;
  b.area = area;
  b.touches_jet = jet;
  b.slug = slug;
  return b;
}

// Spheres on a 5 mm lattice up to 0.4 m; those in the bottom corners (x < 3 cm or > 12 cm,
// y < 3 cm) at `corner_speed`, the rest at 0.5 m/s.
Snapshot bed(double corner_speed) {
  Snapshot s;
  s.width = 0.15;
  s.height = 0.9;
  for (double y = 0.0025; y < 0.4; y += 0.005)
    for (double x = 0.0025; x < 0.15; x += 0.005) {
      const bool corner = (x < 0.03 || x > 0.12) && y < 0.03;
      s.x.push_back(x);
      s.y.push_back(y);
      s.radius.push_back(0.002);
      s.vx.push_back(0.0);
      s.vy.push_back(corner ? corner_speed : 0.5);
    }
  return s;
}

int count(const std::vector<BedLabel>& l, const std::string& text) {
  return static_cast<int>(
      std::count_if(l.begin(), l.end(), [&](const BedLabel& b) { return b.text == text; }));
}

const BedLabel& find(const std::vector<BedLabel>& l, const std::string& text) {
  return *std::find_if(l.begin(), l.end(), [&](const BedLabel& b) { return b.text == text; });
}

}  // namespace

TEST(BedLabels, NameTheJetSlugBubblesFreeboardAndDeadCorners) {
  BubbleView v = analysed_box();
  v.regions = {region(0.075, 0.03, 2e-4, true), region(0.075, 0.33, 6e-3, false, true),
               region(0.04, 0.15, 1e-4),        region(0.10, 0.20, 4e-4),
               region(0.06, 0.25, 2e-4),        region(0.11, 0.10, 3e-4)};
  const std::vector<BedLabel> l = bed_labels(bed(0.0), v);
  EXPECT_EQ(count(l, "jet"), 1);
  EXPECT_EQ(count(l, "slug"), 1);
  EXPECT_DOUBLE_EQ(find(l, "slug").y, 0.33);
  // The three largest of the four bubbles: the 1e-4 m^2 one has no word.
  EXPECT_EQ(count(l, "bubble"), 3);
  for (const BedLabel& b : l) EXPECT_FALSE(b.text == "bubble" && b.x == 0.04);
  // The freeboard halfway between the surface (0.4 m) and the top (0.9 m).
  ASSERT_EQ(count(l, "freeboard"), 1);
  EXPECT_NEAR(bed_surface(v), 0.4, 1e-12);
  EXPECT_NEAR(find(l, "freeboard").y, 0.65, 1e-12);
  EXPECT_NEAR(find(l, "freeboard").x, 0.075, 1e-12);
  // Both resting corners, each at its box's centre (3 cm wide and high).
  ASSERT_EQ(count(l, "dead zone"), 2);
  EXPECT_NEAR(l[l.size() - 2].x, 0.015, 1e-12);
  EXPECT_NEAR(l.back().x, 0.135, 1e-12);
  EXPECT_NEAR(l.back().y, 0.015, 1e-12);
}

TEST(BedLabels, NoDeadZoneWhereTheCornersMoveOrWithoutAJet) {
  BubbleView v = analysed_box();
  v.regions = {region(0.075, 0.03, 2e-4, true)};
  // Corners at 0.3 of the bed's speed: moving, not dead.
  EXPECT_EQ(count(bed_labels(bed(0.15), v), "dead zone"), 0);
  // A bed at rest everywhere: nothing is dead beside anything.
  Snapshot still = bed(0.0);
  std::fill(still.vy.begin(), still.vy.end(), 0.0);
  EXPECT_EQ(count(bed_labels(still, v), "dead zone"), 0);
  // No jet cavity (a uniform inlet): no dead zone, no jet.
  v.regions.clear();
  const auto l = bed_labels(bed(0.0), v);
  EXPECT_EQ(count(l, "dead zone"), 0);
  EXPECT_EQ(count(l, "jet"), 0);
}

TEST(BedLabels, NoFreeboardWordWhereTheBedFillsTheBox) {
  BubbleView v = analysed_box(0.87);  // 3 cm of gas over the bed: under 8 % of 0.9 m
  EXPECT_EQ(count(bed_labels(bed(0.5), v), "freeboard"), 0);
  // A row with a tenth of its cells dense (a sphere thrown up) is still the freeboard; one with
  // a fifth is the bed.
  BubbleView w = analysed_box(0.4);
  w.label[static_cast<std::size_t>(w.grid.index(3, 60))] = kCellDense;
  EXPECT_NEAR(bed_surface(w), 0.4, 1e-12);
  for (int i = 0; i < 4; ++i) w.label[static_cast<std::size_t>(w.grid.index(i, 60))] = kCellDense;
  EXPECT_NEAR(bed_surface(w), 0.61, 1e-12);
}
