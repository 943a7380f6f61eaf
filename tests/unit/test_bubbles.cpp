// Bubble detection, tracking, statistics and output on synthetic particle sets: a packed
// hexagonal monolayer (synthetic_bed.hpp) with circular holes cut out.
//
// The expected size of a hole, from the construction. Removing the spheres whose centres lie
// within the hole's radius plus one particle radius empties their cells of the hexagonal
// lattice: each sphere of a packed layer owns a hexagon of area sqrt(3)/2 d^2 whose edges pass
// through its contact points, that is through the rims of its neighbours, and what remains of
// the neighbours inside it are their rims' thin outer slivers. So the construction is, to the
// detector, void (eps = 1) over the union H of the removed hexagons and packed (eps_b = 0.3954)
// outside. The detector thresholds the void fraction over a 10 mm window centred on each 2 mm
// cell, 1 - (1 - f) (1 - eps_b) with f the share of the window in H: a cell is void when
// f > (0.8 - eps_b) / (1 - eps_b) = 0.669. expected_d_eq applies exactly that to H (f sampled on
// 20 x 20 points of each window; a point lies in H when its nearest lattice site was removed),
// independently of the detector's sphere volumes. For hole radii of 8 to 40 mm at 6 positions
// each the detected D_e agrees to within 2.7 % (4.5 % at 6 mm: a handful of boundary cells).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/bubbles.hpp"
#include "core/binary_io.hpp"
#include "core/errors.hpp"
#include "scene/lattice.hpp"
#include "synthetic_bed.hpp"

using fluidbed::BedGeometry;
using fluidbed::Bubble;
using fluidbed::BubbleAnalysis;
using fluidbed::BubbleEvent;
using fluidbed::BubbleFrame;
using fluidbed::BubbleHistory;
using fluidbed::BubbleRow;
using fluidbed::BubbleSettings;
using fluidbed::Particles;
using fluidbed::Regime;
using fluidbed::testing::hex_bed;
using fluidbed::testing::Hole;

namespace {

constexpr double kD = 0.004;                    // m, particle diameter
constexpr double kWidth = 0.15;                 // m
constexpr double kTop = 0.2;                    // m, highest centre of the synthetic bed
const double kRow = std::sqrt(3.0) / 2.0 * kD;  // m, row spacing of the hexagonal layer

// True when the point's nearest site of hex_bed's lattice was removed by one of the holes.
bool in_removed_hexagon(double x, double y, const std::vector<Hole>& holes) {
  const double r = 0.5 * kD;
  const int row0 = static_cast<int>(std::lround((y - r) / kRow));
  double best = std::numeric_limits<double>::infinity(), sx = 0.0, sy = 0.0;
  for (int row = std::max(0, row0 - 1); row <= row0 + 1; ++row) {
    const double yr = r + row * kRow, shift = row % 2 == 1 ? r : 0.0;
    const int col0 = static_cast<int>(std::lround((x - r - shift) / kD));
    for (int col = col0 - 1; col <= col0 + 1; ++col) {
      const double xs = r + shift + col * kD;
      const double d2 = (xs - x) * (xs - x) + (yr - y) * (yr - y);
      if (d2 < best) {
        best = d2;
        sx = xs;
        sy = yr;
      }
    }
  }
  for (const Hole& h : holes)
    if (std::hypot(sx - h.x, sy - h.y) < h.radius + r) return true;
  return false;
}

// D_e of the void the detector should see for these holes (see the top of this file), on its
// grid of 2 mm cells with a window of 10 mm and the threshold 0.8.
double expected_d_eq(const std::vector<Hole>& holes) {
  constexpr double cell = 0.002, window = 0.01;
  constexpr int n = 20;  // samples per window side
  const double eps_b = 1.0 - std::numbers::pi / (2.0 * std::sqrt(3.0)) * 2.0 / 3.0;
  const double f_void = (0.8 - eps_b) / (1.0 - eps_b);
  int cells = 0;
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 75; ++i) {
      const double cx = (i + 0.5) * cell, cy = (j + 0.5) * cell;
      bool near = false;
      for (const Hole& h : holes)
        near = near || std::hypot(cx - h.x, cy - h.y) < h.radius + kD + window;
      if (!near) continue;
      int in = 0;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          in += in_removed_hexagon(cx - 0.5 * window + (a + 0.5) * window / n,
                                   cy - 0.5 * window + (b + 0.5) * window / n, holes);
      if (in > f_void * n * n) ++cells;
    }
  return std::sqrt(4.0 * cells * cell * cell / std::numbers::pi);
}

const Bubble* find_id(const BubbleFrame& f, int id) {
  for (const Bubble& b : f.regions)
    if (b.id == id) return &b;
  return nullptr;
}

BubbleFrame one_frame(const Particles& p, const BubbleSettings& s = {}, const BedGeometry& g = {}) {
  BubbleAnalysis a(s, g);
  return a.analyse(0.01, p);
}

}  // namespace

TEST(BubbleDetection, PackedBedHasNoBubbles) {
  // The hexagonal layer, and the paper's looser start (rows one diameter apart, eps 0.48).
  const BubbleFrame f = one_frame(hex_bed(kWidth, kTop));
  EXPECT_TRUE(f.regions.empty());
  EXPECT_FALSE(f.spout);
  Particles lattice;
  const auto sites = fluidbed::lattice_sites(kWidth, 0.2, kD);
  lattice.resize(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    lattice.x[i] = sites[i].x;
    lattice.y[i] = sites[i].y;
    lattice.set_sphere(i, kD, 2700.0);
  }
  EXPECT_TRUE(one_frame(lattice).regions.empty());
  // The surface: the top of the highest dense cell of each column; the top row of spheres has
  // its centres at 0.1994 m and reaches 0.2014 m; a cell there is dense once the spheres fill
  // a fifth of it, so the surface lies within a radius of the top centres, rounded up to the
  // top of a 2 mm cell.
  const double top = 0.002 + 57 * kRow;
  for (double h : f.surface) {
    EXPECT_GT(h, top - 0.5 * kD);
    EXPECT_LE(h, top + 0.5 * kD + 0.002);
  }
}

TEST(BubbleDetection, HolesOfKnownDiameterAreFoundWithTheirSize) {
  const std::vector<Hole> holes = {{0.035, 0.05, 0.010}, {0.11, 0.08, 0.015}, {0.05, 0.14, 0.020}};
  const BubbleFrame f = one_frame(hex_bed(kWidth, kTop, holes));
  ASSERT_EQ(f.regions.size(), 3u);
  for (const Hole& h : holes) {
    const Bubble* found = nullptr;
    for (const Bubble& b : f.regions)
      if (std::hypot(b.x - h.x, b.y - h.y) < h.radius) found = &b;
    ASSERT_NE(found, nullptr) << "hole at " << h.x << ", " << h.y;
    const double expected = expected_d_eq({h});
    EXPECT_NEAR(found->d_eq, expected, 0.05 * expected);
    EXPECT_NEAR(found->area, std::numbers::pi / 4.0 * found->d_eq * found->d_eq, 1e-12);
    EXPECT_NEAR(found->x, h.x, 0.001);
    EXPECT_NEAR(found->y, h.y, 0.001);
    EXPECT_NEAR(found->aspect_ratio, 1.0, 0.15);
    EXPECT_NEAR(found->width, expected, 0.15 * expected);
    EXPECT_FALSE(found->touches_wall);
    EXPECT_FALSE(found->touches_jet);
    EXPECT_FALSE(found->slug);
  }
  // Hole radii from 10 to 30 mm (D_e 20 to 60 mm) at several positions relative to the lattice
  // and the cells.
  for (double r : {0.010, 0.0125, 0.015, 0.02, 0.03}) {
    for (int k = 0; k < 6; ++k) {
      const Hole h{0.06 + 0.00115 * k, 0.08 + 0.00094 * k, r};
      const BubbleFrame g = one_frame(hex_bed(kWidth, kTop, {h}));
      ASSERT_EQ(g.regions.size(), 1u);
      const double expected = expected_d_eq({h});
      EXPECT_NEAR(g.regions[0].d_eq, expected, 0.05 * expected) << "radius " << r << " k " << k;
    }
  }
}

// The outlines drawn over frames: every edge separates one of the region's cells from a cell
// outside it, each cell of the region contributes its outside sides, and the edges close (every
// corner is met an even number of times).
TEST(BubbleDetection, OutlineIsTheClosedBoundaryOfTheRegionsCells) {
  BubbleAnalysis a({}, {});
  const BubbleFrame& f = a.analyse(0.01, hex_bed(kWidth, kTop, {{0.07, 0.08, 0.012}}));
  ASSERT_EQ(f.regions.size(), 1u);
  const fluidbed::FineGrid& g = a.void_fraction().grid;
  std::vector<float> xy;
  fluidbed::outline_edges(f, g, xy);
  ASSERT_EQ(xy.size() % 4, 0u);
  int outside_sides = 0;
  auto in = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < g.nx && j < g.ny && f.label[g.index(i, j)] == 0;
  };
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (in(i, j))
        outside_sides += !in(i - 1, j) + !in(i + 1, j) + !in(i, j - 1) + !in(i, j + 1);
  EXPECT_EQ(static_cast<int>(xy.size() / 4), outside_sides);
  EXPECT_GT(outside_sides, 8);
  std::map<std::pair<long, long>, int> corners;
  auto key = [&](float x, float y) {
    return std::make_pair(std::lround(x / g.dx), std::lround(y / g.dy));
  };
  for (std::size_t k = 0; k < xy.size(); k += 4) {
    const float x0 = xy[k], y0 = xy[k + 1], x1 = xy[k + 2], y1 = xy[k + 3];
    EXPECT_NEAR(std::hypot(x1 - x0, y1 - y0), x0 == x1 ? g.dy : g.dx, 1e-6);
    ++corners[key(x0, y0)];
    ++corners[key(x1, y1)];
    // The edge lies within the hole's extent (radius plus a window).
    EXPECT_LT(std::hypot(0.5 * (x0 + x1) - 0.07, 0.5 * (y0 + y1) - 0.08), 0.012 + 0.01);
  }
  for (const auto& [c, n] : corners) EXPECT_EQ(n % 2, 0) << c.first << "," << c.second;
  // A packed bed has nothing to outline.
  const BubbleFrame& none = a.analyse(0.02, hex_bed(kWidth, kTop));
  xy.clear();
  fluidbed::outline_edges(none, g, xy);
  EXPECT_TRUE(xy.empty());
}

TEST(BubbleDetection, TouchingHolesAreOneBubbleSeparateHolesTwo) {
  // Two holes (radius 10 mm) whose discs touch: one region, of both holes' area.
  const std::vector<Hole> touching = {{0.065, 0.08, 0.010}, {0.085, 0.08, 0.010}};
  const BubbleFrame f = one_frame(hex_bed(kWidth, kTop, touching));
  ASSERT_EQ(f.regions.size(), 1u);
  const double expected = expected_d_eq(touching);
  EXPECT_NEAR(f.regions[0].d_eq, expected, 0.05 * expected);
  EXPECT_NEAR(f.regions[0].x, 0.075, 0.001);
  EXPECT_GT(f.regions[0].width, 1.6 * f.regions[0].height);
  // Three particle layers between the removed discs: two bubbles.
  const std::vector<Hole> apart = {{0.055, 0.08, 0.010}, {0.095, 0.08, 0.010}};
  EXPECT_EQ(one_frame(hex_bed(kWidth, kTop, apart)).regions.size(), 2u);
}

TEST(BubbleDetection, HoleWiderThanSixTenthsOfTheBedIsASlug) {
  // A round hole 98 mm wide as detected (0.65 of the bed) in a bed 0.3 m deep, and one 62 mm
  // wide (0.41).
  const BubbleFrame wide = one_frame(hex_bed(kWidth, 0.3, {{0.075, 0.14, 0.048}}));
  ASSERT_EQ(wide.regions.size(), 1u);
  EXPECT_GT(wide.regions[0].width, 0.6 * kWidth);
  EXPECT_TRUE(wide.regions[0].slug);
  const BubbleFrame narrow = one_frame(hex_bed(kWidth, 0.3, {{0.075, 0.14, 0.030}}));
  ASSERT_EQ(narrow.regions.size(), 1u);
  EXPECT_FALSE(narrow.regions[0].slug);
  // A flat slug from wall to wall, the bed above it resting on nothing (a particle piston): the
  // piston is bed (the surface is its top), so the slug is inside the bed.
  Particles p = hex_bed(kWidth, 0.3);
  Particles q;
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.y[i] < 0.1 || p.y[i] > 0.13) keep.push_back(i);
  q.resize(keep.size());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    q.x[k] = p.x[keep[k]];
    q.y[k] = p.y[keep[k]];
    q.set_sphere(k, kD, 2700.0);
  }
  const BubbleFrame band = one_frame(q);
  ASSERT_EQ(band.regions.size(), 1u);
  EXPECT_TRUE(band.regions[0].slug);
  EXPECT_TRUE(band.regions[0].touches_wall);
  EXPECT_NEAR(band.regions[0].width, kWidth, 1e-12);
  EXPECT_GT(band.surface[40], 0.3);
}

TEST(BubbleDetection, HoleOpenToTheTopIsNotABubble) {
  // A hole cut through the surface: part of the freeboard. Beside it a closed hole is a bubble.
  const BubbleFrame f =
      one_frame(hex_bed(kWidth, kTop, {{0.04, kTop - 0.005, 0.015}, {0.11, 0.1, 0.012}}));
  ASSERT_EQ(f.regions.size(), 1u);
  EXPECT_NEAR(f.regions[0].x, 0.11, 0.001);
  const fluidbed::FineGrid grid = fluidbed::make_fine_grid(kWidth, 0.9, 0.004, 0.002, kD);
  EXPECT_EQ(f.label[grid.index(20, static_cast<int>((kTop - 0.005) / 0.002))],
            fluidbed::kCellFreeboard);
  // The surface dips into the open hole.
  EXPECT_LT(f.surface[20], kTop - 0.01);
  // Under a roof of four particle rows the hole is closed, a bubble; 18 mm higher it opens.
  EXPECT_EQ(one_frame(hex_bed(kWidth, kTop, {{0.075, kTop - 0.026, 0.012}})).regions.size(), 1u);
  EXPECT_EQ(one_frame(hex_bed(kWidth, kTop, {{0.075, kTop - 0.008, 0.012}})).regions.size(), 0u);
}

TEST(BubbleDetection, CavityAtTheJetIsFlaggedJet) {
  // A cavity on the bottom over the paper's central slot: the jet cavity. The same cavity at the
  // bottom away from the slot is a bubble (touching the floor, not the jet).
  const BubbleFrame f = one_frame(hex_bed(kWidth, kTop, {{0.075, 0.0, 0.015}}));
  ASSERT_EQ(f.regions.size(), 1u);
  EXPECT_TRUE(f.regions[0].touches_jet);
  EXPECT_FALSE(f.regions[0].slug);
  BubbleHistory h;
  h.add(f, 0.01);
  EXPECT_TRUE(h.samples.empty());  // not a bubble
  EXPECT_TRUE(h.frames[0].jet_cavity);
  const BubbleFrame off = one_frame(hex_bed(kWidth, kTop, {{0.03, 0.0, 0.015}}));
  ASSERT_EQ(off.regions.size(), 1u);
  EXPECT_FALSE(off.regions[0].touches_jet);
  // Without jets (a uniform distributor) nothing is a jet cavity.
  BedGeometry uniform;
  uniform.jets.clear();
  const BubbleFrame u = one_frame(hex_bed(kWidth, kTop, {{0.075, 0.0, 0.015}}), {}, uniform);
  ASSERT_EQ(u.regions.size(), 1u);
  EXPECT_FALSE(u.regions[0].touches_jet);
  // A jet cavity reaching the freeboard: the jet spouts.
  std::vector<Hole> spout;
  for (double y = 0.0; y <= kTop + 0.01; y += 0.005) spout.push_back({0.075, y, 0.008});
  const BubbleFrame sp = one_frame(hex_bed(kWidth, kTop, spout));
  EXPECT_TRUE(sp.regions.empty());
  EXPECT_TRUE(sp.spout);
}

TEST(BubbleTracking, HoleMovedIsTrackedWithItsVelocity) {
  // A hole rising two rows (6.93 mm) per 10 ms, then moving along the lattice's diagonal (one
  // row up, half a diameter across): the removed pattern is the same each frame, shifted by a
  // known distance. The velocity from the centroids is right within 5 %.
  BubbleAnalysis a({}, {});
  const double x0 = 0.07, y0 = 0.05;
  double t = 0.0;
  int id = -1;
  for (int k = 0; k < 4; ++k) {
    t += 0.01;
    const BubbleFrame& f = a.analyse(t, hex_bed(kWidth, kTop, {{x0, y0 + 2 * k * kRow, 0.010}}));
    ASSERT_EQ(f.regions.size(), 1u);
    if (k == 0) {
      id = f.regions[0].id;
      EXPECT_EQ(f.regions[0].event, BubbleEvent::formed);
      EXPECT_FALSE(f.regions[0].has_velocity);
      continue;
    }
    EXPECT_EQ(f.regions[0].id, id);
    EXPECT_EQ(f.regions[0].event, BubbleEvent::none);
    ASSERT_TRUE(f.regions[0].has_velocity);
    const double v = 2 * kRow / 0.01;
    EXPECT_NEAR(f.regions[0].vy, v, 0.05 * v);
    EXPECT_NEAR(f.regions[0].vx, 0.0, 0.05 * v);
  }
  BubbleAnalysis b({}, {});
  for (int k = 0; k < 4; ++k) {
    const BubbleFrame& f = b.analyse(
        0.01 * (k + 1), hex_bed(kWidth, kTop, {{x0 + 0.5 * kD * k, y0 + kRow * k, 0.012}}));
    ASSERT_EQ(f.regions.size(), 1u);
    if (k == 0) continue;
    ASSERT_TRUE(f.regions[0].has_velocity);
    const double speed = std::hypot(f.regions[0].vx - 0.2, f.regions[0].vy - kRow / 0.01);
    EXPECT_LT(speed, 0.05 * (kD / 0.01));
  }
}

TEST(BubbleTracking, HoleMovedFurtherThanItsSizeKeepsItsId) {
  // 28 mm between frames for a hole of 20 mm: no overlap, matched by the nearest centroid.
  BubbleAnalysis a({}, {});
  const BubbleFrame f0 = a.analyse(0.01, hex_bed(kWidth, kTop, {{0.075, 0.05, 0.010}}));
  const BubbleFrame& f1 = a.analyse(0.02, hex_bed(kWidth, kTop, {{0.075, 0.05 + 8 * kRow, 0.010}}));
  ASSERT_EQ(f1.regions.size(), 1u);
  EXPECT_EQ(f1.regions[0].id, f0.regions[0].id);
  EXPECT_TRUE(f1.ended.empty());
  ASSERT_TRUE(f1.regions[0].has_velocity);
  EXPECT_NEAR(f1.regions[0].vy, 8 * kRow / 0.01, 0.05 * 8 * kRow / 0.01);
}

TEST(BubbleTracking, EventsFormedCoalescedSplitEruptedVanished) {
  // A bed 0.12 m deep, so that the last bubble can reach its surface. Every id here lives one or
  // two frames: the statistics count them all (min_track_frames = 1).
  const double top = 0.12;
  BubbleSettings every_id;
  every_id.min_track_frames = 1;
  BubbleAnalysis a(every_id, {});
  std::vector<BubbleRow> rows;
  const auto frame = [&](double t, const std::vector<Hole>& holes) -> const BubbleFrame& {
    const BubbleFrame& f = a.analyse(t, hex_bed(kWidth, top, holes));
    a.append_rows(rows);
    return f;
  };
  // 1: the jet cavity alone; it gets an id but no event and no row.
  const BubbleFrame& f1 = frame(0.01, {{0.075, 0.0, 0.012}});
  ASSERT_EQ(f1.regions.size(), 1u);
  ASSERT_TRUE(f1.regions[0].touches_jet);
  const int jet_id = f1.regions[0].id;
  EXPECT_TRUE(rows.empty());
  // 2: the cavity has detached (a floor of two particle rows below it): formed at the jet.
  const BubbleFrame& f2 = frame(0.02, {{0.075, 0.022, 0.012}});
  ASSERT_EQ(f2.regions.size(), 1u);
  EXPECT_FALSE(f2.regions[0].touches_jet);
  EXPECT_EQ(f2.regions[0].event, BubbleEvent::formed);
  EXPECT_TRUE(f2.regions[0].from_jet);
  EXPECT_FALSE(f2.regions[0].has_velocity);  // the centroid jumped: no velocity
  const int a_id = f2.regions[0].id;
  EXPECT_EQ(a_id, jet_id);  // the region is the same gas: it keeps its id
  // 3: it rises; a second bubble appears beside it (formed, not at the jet).
  const BubbleFrame& f3 = frame(0.03, {{0.075, 0.022 + 2 * kRow, 0.012}, {0.075, 0.09, 0.012}});
  ASSERT_EQ(f3.regions.size(), 2u);
  ASSERT_NE(find_id(f3, a_id), nullptr);
  EXPECT_TRUE(find_id(f3, a_id)->has_velocity);
  int b_id = -1;
  for (const Bubble& b : f3.regions)
    if (b.id != a_id) {
      b_id = b.id;
      EXPECT_EQ(b.event, BubbleEvent::formed);
      EXPECT_FALSE(b.from_jet);
    }
  // 4: they merge: one region, continuing the id of the parent with the larger overlap, with
  // the event coalesced and no velocity (the centroid jumped).
  const BubbleFrame& f4 = frame(0.04, {{0.075, 0.05, 0.012}, {0.075, 0.075, 0.012}});
  ASSERT_EQ(f4.regions.size(), 1u);
  EXPECT_EQ(f4.regions[0].event, BubbleEvent::coalesced);
  EXPECT_TRUE(f4.regions[0].id == a_id || f4.regions[0].id == b_id);
  EXPECT_FALSE(f4.regions[0].has_velocity);
  const int m_id = f4.regions[0].id;
  // 5: it splits in two: the larger part keeps the id, the other is a new bubble (split).
  const BubbleFrame& f5 = frame(0.05, {{0.075, 0.045, 0.010}, {0.075, 0.084, 0.013}});
  ASSERT_EQ(f5.regions.size(), 2u);
  ASSERT_NE(find_id(f5, m_id), nullptr);
  int split_id = -1;
  for (const Bubble& b : f5.regions)
    if (b.id != m_id) {
      split_id = b.id;
      EXPECT_EQ(b.event, BubbleEvent::split);
    }
  EXPECT_GT(split_id, m_id);
  // 6: the upper one opens to the freeboard (erupted); the lower one collapses (vanished).
  const BubbleFrame& f6 = frame(0.06, {{0.075, 0.11, 0.014}});
  EXPECT_TRUE(f6.regions.empty());
  ASSERT_EQ(f6.ended.size(), 2u);
  int erupted = 0, vanished = 0;
  for (const Bubble& b : f6.ended) {
    if (b.event == BubbleEvent::erupted) {
      ++erupted;
      EXPECT_GT(b.y, 0.07);
    }
    if (b.event == BubbleEvent::vanished) {
      ++vanished;
      EXPECT_LT(b.y, 0.06);
    }
  }
  EXPECT_EQ(erupted, 1);
  EXPECT_EQ(vanished, 1);
  // The rows: one per bubble per frame plus one per ended bubble, at the frame's time.
  EXPECT_EQ(rows.size(), 1u + 2u + 1u + 2u + 2u);
  EXPECT_EQ(rows.back().t, 0.06);
  // Statistics over frames 2-6 (five intervals of 10 ms): 2 formed (one at the jet), 1
  // coalescence, 1 split, 1 eruption.
  const fluidbed::BubbleStatistics st = a.statistics(0.0);
  EXPECT_EQ(st.frames, 5);
  EXPECT_NEAR(st.duration, 0.05, 1e-12);
  EXPECT_EQ(st.formed, 2);
  EXPECT_EQ(st.formed_at_jet, 1);
  EXPECT_EQ(st.coalesced, 1);
  EXPECT_EQ(st.split, 1);
  EXPECT_EQ(st.erupted, 1);
  EXPECT_EQ(st.vanished, 1);
  EXPECT_NEAR(st.formed_per_s, 40.0, 1e-9);
  EXPECT_NEAR(st.eruptions_per_s, 20.0, 1e-9);
  EXPECT_EQ(st.regime, Regime::bubbling);
}

TEST(BubbleStatistics, MeansOverBubbleFramesAndThePyleHarrisonReference) {
  // A hole of D_e 20 mm (removal radius 12 mm) rising 6.93 mm per 10 ms from t = 0.01 s; averaging
  // from 0.025 s.
  BubbleAnalysis a({}, {});
  for (int k = 0; k < 6; ++k)
    a.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, {{0.07, 0.05 + 2 * k * kRow, 0.010}}));
  const fluidbed::BubbleStatistics st = a.statistics(0.025);
  EXPECT_EQ(st.frames, 4);  // t = 0.03 .. 0.06
  EXPECT_EQ(st.bubble_frames, 4);
  EXPECT_EQ(st.velocity_samples, 4);
  const double d_eq = expected_d_eq({{0.07, 0.05, 0.010}});
  EXPECT_NEAR(st.mean_d_eq_m, d_eq, 0.05 * d_eq);
  EXPECT_NEAR(st.mean_rise_velocity_m_s, 2 * kRow / 0.01, 0.03 * 2 * kRow / 0.01);
  EXPECT_NEAR(st.mean_rise_velocity_2d_ref_m_s, 0.5 * std::sqrt(9.81 * st.mean_d_eq_m), 0.002);
  EXPECT_EQ(st.formed, 0);  // formed at t = 0.01, before the window
  EXPECT_EQ(st.slugging_fraction, 0.0);
  EXPECT_EQ(st.regime, Regime::fixed);  // nothing formed in the window
  // The first frame has no interval before it: its bubble's `formed` counts in no window.
  EXPECT_EQ(a.regime(0.0, 1.0), Regime::fixed);
  const nlohmann::json j = fluidbed::to_json(st);
  for (const char* key : {"formed_per_s", "eruptions_per_s", "mean_d_eq_m",
                          "mean_rise_velocity_m_s", "slugging_fraction", "regime"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["regime"], "fixed");
  EXPECT_NEAR(j["mean_d_eq_m"].get<double>(), st.mean_d_eq_m, 1e-15);
  // No bubble at all: means are null, not 0.
  BubbleAnalysis empty({}, {});
  empty.analyse(0.01, hex_bed(kWidth, kTop));
  empty.analyse(0.02, hex_bed(kWidth, kTop));
  const nlohmann::json e = fluidbed::to_json(empty.statistics(0.0));
  EXPECT_TRUE(e["mean_d_eq_m"].is_null());
  EXPECT_TRUE(e["mean_rise_velocity_m_s"].is_null());
  EXPECT_EQ(e["regime"], "fixed");
  EXPECT_EQ(e["formed_per_s"], 0.0);
}

TEST(BubbleStatistics, RegimeRule) {
  // 100 frames of 10 ms after a first one; each case sets what the rule looks at: bubbles formed
  // (ids seen in 3 frames), frames with a slug, frames with the jet open to the freeboard.
  const BubbleSettings s;
  const auto history = [](int formed, int slug, int spout) {
    BubbleHistory h;
    h.frames.push_back({0.0, 0.0, false, false, true});
    for (int k = 0; k < 100; ++k) {
      const double t = 0.01 * (k + 1);
      h.frames.push_back({t, 0.01, k < slug, k < spout, true});
      if (k < formed) {
        BubbleHistory::Sample q;
        q.t = t;
        q.id = k;
        q.d_eq = 0.02;
        q.event = BubbleEvent::formed;
        h.samples.push_back(q);
        h.id_frames.push_back(3);
      }
    }
    return h;
  };
  constexpr double inf = std::numeric_limits<double>::infinity();
  const auto regime = [&](int formed, int slug, int spout, double t0 = 0.0,
                          double t1 = std::numeric_limits<double>::infinity()) {
    return history(formed, slug, spout).summarize(t0, t1, s, 9.81).regime;
  };
  EXPECT_EQ(regime(0, 0, 0), Regime::fixed);
  EXPECT_EQ(regime(3, 0, 0), Regime::bubbling);
  EXPECT_EQ(regime(3, 10, 0), Regime::bubbling);
  EXPECT_EQ(regime(0, 5, 0), Regime::bubbling);
  EXPECT_EQ(regime(3, 25, 0), Regime::slugging);
  EXPECT_EQ(regime(0, 0, 50), Regime::spouting);
  EXPECT_EQ(regime(3, 60, 49), Regime::slugging);
  const auto st = history(3, 25, 0).summarize(0.0, inf, s, 9.81);
  EXPECT_EQ(st.frames, 100);
  EXPECT_NEAR(st.duration, 1.0, 1e-12);
  EXPECT_NEAR(st.slugging_fraction, 0.25, 1e-12);
  EXPECT_NEAR(st.formed_per_s, 3.0, 1e-9);
  EXPECT_NEAR(st.jet_cavity_fraction, 1.0, 1e-12);
  // Per window: the first 0.25 s hold the slugs and the bubbles.
  EXPECT_EQ(regime(3, 25, 0, 0.0, 0.25), Regime::slugging);
  EXPECT_EQ(regime(3, 25, 0, 0.5, 1.0), Regime::fixed);
  // Ids seen in fewer than min_track_frames frames are flicker: not counted.
  BubbleHistory flicker = history(3, 0, 0);
  flicker.id_frames = {1, 2, 3};
  const auto f = flicker.summarize(0.0, inf, s, 9.81);
  EXPECT_EQ(f.formed, 1);
  EXPECT_EQ(f.flicker_ids, 2);
  EXPECT_STREQ(fluidbed::to_string(Regime::spouting), "spouting");
}

TEST(BubbleStatistics, FlickerEruptionAndBursts) {
  // Frame by frame on synthetic beds (0.12 m deep): a hole seen in one frame only is flicker; a
  // bubble just under the surface that fills in (its roof, 18 mm, thinner than its 21 mm) has
  // erupted; two such bubbles ending 10 ms apart are one burst; a bubble deep in the bed that
  // fills in has vanished.
  const double top = 0.12;
  BubbleAnalysis a({}, {});
  std::vector<BubbleRow> rows;
  const std::vector<std::vector<Hole>> frames = {
      {},
      {{0.04, 0.05, 0.008}},                        // flicker: one frame
      {{0.04, 0.095, 0.011}, {0.11, 0.03, 0.010}},  // near the surface; deep
      {{0.04, 0.095, 0.011}, {0.11, 0.03, 0.010}, {0.11, 0.095, 0.011}},
      {{0.04, 0.095, 0.011}, {0.11, 0.03, 0.010}, {0.11, 0.095, 0.011}},
      {{0.11, 0.03, 0.010}, {0.11, 0.095, 0.011}},  // the first fills in: erupted
      {},                                           // both others fill in
  };
  for (std::size_t k = 0; k < frames.size(); ++k) {
    a.analyse(0.01 * static_cast<double>(k + 1), hex_bed(kWidth, top, frames[k]));
    a.append_rows(rows);
  }
  int erupted = 0, vanished = 0;
  for (const BubbleRow& r : rows) {
    if (r.event == BubbleEvent::erupted) {
      ++erupted;
      EXPECT_GT(r.y, 0.08);
    }
    if (r.event == BubbleEvent::vanished) {
      ++vanished;
      EXPECT_LT(r.y, 0.08);
    }
  }
  EXPECT_EQ(erupted, 2);
  EXPECT_EQ(vanished, 2);  // the flicker and the deep one
  const fluidbed::BubbleStatistics st = a.statistics(0.0);
  EXPECT_EQ(st.flicker_ids, 1);
  EXPECT_EQ(st.formed, 3);
  EXPECT_EQ(st.erupted, 2);
  EXPECT_EQ(st.vanished, 1);
  EXPECT_EQ(st.eruption_bursts, 1);  // 10 ms apart, within eruption_gap
  EXPECT_NEAR(st.eruptions_per_s, 1.0 / 0.06, 1e-9);
  EXPECT_NEAR(st.erupted_bubbles_per_s, 2.0 / 0.06, 1e-9);
}

TEST(BubbleCsv, OneRowPerBubbleWithTheIssuesColumns) {
  std::vector<BubbleRow> rows(2);
  rows[0] = {0.25, 3, 0.075, 0.1, 0.024, 4.5e-4, 0.026, 0.022, 0.01, 0.35, true, BubbleEvent::none};
  rows[1] = {0.25, 4, 0.05, 0.12, 0.01, 8e-5, 0.01, 0.01, 0.0, 0.0, false, BubbleEvent::split};
  std::ostringstream os;
  fluidbed::write_bubbles_csv_header(os);
  fluidbed::write_bubbles_csv_rows(os, rows);
  EXPECT_EQ(os.str(),
            "t,id,x,y,d_eq,area,width,height,vx,vy,event\n"
            "0.25,3,0.075,0.1,0.024,0.00045,0.026,0.022,0.01,0.35,\n"
            "0.25,4,0.05,0.12,0.01,8e-05,0.01,0.01,,,split\n");
}

TEST(BubbleSettings, BadParametersAreOneLineInputErrorsNamingTheKey) {
  const BedGeometry g;
  const auto expect_error = [&](BubbleSettings s, const std::string& key) {
    try {
      BubbleAnalysis a(s, g);
      ADD_FAILURE() << "no error for " << key;
    } catch (const fluidbed::InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(key + " ", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  for (double t : {0.0, 1.0, -0.2, 1.5, std::nan("")}) {
    BubbleSettings s;
    s.threshold = t;
    expect_error(s, "bubbles.threshold");
  }
  for (double i : {0.0, -0.01, std::nan("")}) {
    BubbleSettings s;
    s.interval = i;
    expect_error(s, "bubbles.interval");
  }
  BubbleSettings s;
  s.min_diameter = -0.001;
  expect_error(s, "bubbles.min_diameter");
  s = BubbleSettings{};
  s.slug_fraction = 0.0;
  expect_error(s, "bubbles.slug_fraction");
  s = BubbleSettings{};
  s.cell_size = 0.0;
  expect_error(s, "bubbles.cell_size");
  // The defaults for another particle size.
  const BubbleSettings d = fluidbed::default_bubble_settings(0.002);
  EXPECT_DOUBLE_EQ(d.min_diameter, 0.004);
  EXPECT_DOUBLE_EQ(d.cell_size, 0.001);
  EXPECT_NO_THROW(fluidbed::validate(BubbleSettings{}, g));
}

TEST(BubbleAnalysis, CheckpointResumesWithTheSameResults) {
  // Frames 1-3, a checkpoint, frames 4-6: the same rows and statistics as 1-6 in one go.
  const auto holes = [](int k) {
    return std::vector<Hole>{{0.05, 0.04 + 2 * k * kRow, 0.010}, {0.11, 0.16 - 0.004 * k, 0.012}};
  };
  BubbleAnalysis whole({}, {});
  std::vector<BubbleRow> whole_rows;
  for (int k = 0; k < 6; ++k) {
    whole.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, holes(k)));
    if (k >= 3) whole.append_rows(whole_rows);
  }
  BubbleAnalysis first({}, {});
  for (int k = 0; k < 3; ++k) first.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, holes(k)));
  std::stringstream state;
  fluidbed::BinarySink sink(state);
  first.save(sink);
  BubbleAnalysis resumed({}, {});
  const std::string origin = "checkpoint";
  fluidbed::BinarySource source(state, origin);
  resumed.restore(source);
  std::vector<BubbleRow> resumed_rows;
  for (int k = 3; k < 6; ++k) {
    resumed.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, holes(k)));
    resumed.append_rows(resumed_rows);
  }
  std::ostringstream a, b;
  fluidbed::write_bubbles_csv_rows(a, whole_rows);
  fluidbed::write_bubbles_csv_rows(b, resumed_rows);
  EXPECT_FALSE(whole_rows.empty());
  EXPECT_EQ(a.str(), b.str());
  EXPECT_EQ(fluidbed::to_json(whole.statistics(0.0)).dump(),
            fluidbed::to_json(resumed.statistics(0.0)).dump());
  // A truncated state is an InputError naming its origin.
  std::stringstream cut(state.str().substr(0, 40));
  BubbleAnalysis broken({}, {});
  fluidbed::BinarySource cut_source(cut, origin);
  EXPECT_THROW(broken.restore(cut_source), fluidbed::InputError);
}

TEST(BubbleAnalysis, CheckpointOfAnotherLayoutOrGridIsRefusedInOneLine) {
  BubbleAnalysis a({}, {});
  a.analyse(0.01, hex_bed(kWidth, kTop, {{0.05, 0.08, 0.010}}));
  std::stringstream saved;
  fluidbed::BinarySink sink(saved);
  a.save(sink);
  const std::string origin = "run/checkpoint.bin";
  const auto refusal = [&](BubbleAnalysis& into, const std::string& bytes) {
    std::stringstream in(bytes);
    fluidbed::BinarySource source(in, origin);
    try {
      into.restore(source);
    } catch (const fluidbed::InputError& e) {
      return std::string(e.what());
    }
    return std::string("restored");
  };
  // The same settings: restored.
  BubbleAnalysis same({}, {});
  EXPECT_EQ(refusal(same, saved.str()), "restored");
  // An analysis on another fine grid: the tracker's cell labels do not fit it.
  BubbleSettings coarse;
  coarse.cell_size = 0.004;
  BubbleAnalysis other(coarse, {});
  EXPECT_EQ(refusal(other, saved.str()),
            "run/checkpoint.bin: state file is inconsistent (array sizes)");
  // Another version of the section (its tag's last two characters).
  std::string older = saved.str();
  older[6] = '0';
  older[7] = '1';
  BubbleAnalysis fresh({}, {});
  EXPECT_EQ(refusal(fresh, older),
            "run/checkpoint.bin: state file is written by another version of fluidbed (bubble "
            "analysis 01, this one reads 02): run it again from its start");
  // The layout before the tags (a four-byte magic number, then the tracker's).
  std::string legacy = saved.str();
  legacy.replace(0, 8, std::string("AHUB1BUB"));
  BubbleAnalysis fresh2({}, {});
  EXPECT_EQ(refusal(fresh2, legacy), "run/checkpoint.bin: state file is not a bubble analysis's");
}
