// Bubble detection and tracking on synthetic particle sets: a packed hexagonal monolayer with
// circular holes cut out (bubble_test_bed.hpp, which says how the expected sizes are found).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/bubbles.hpp"
#include "bubble_test_bed.hpp"
#include "scene/lattice.hpp"


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
      if (in(i, j)) outside_sides += !in(i - 1, j) + !in(i + 1, j) + !in(i, j - 1) + !in(i, j + 1);
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
