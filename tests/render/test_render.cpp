// Offscreen pictures (OSMesa) of synthetic snapshots: what is drawn lands on the pixels the layout
// gives, in the colour the colour map gives, and the same snapshot gives the same pixels.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <stb_truetype.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "render/colour_modes.hpp"
#include "render/font.hpp"
#include "render/font_file.hpp"
#include "render/gl_context.hpp"
#include "render/layout.hpp"
#include "render/renderer.hpp"
#include "render_support.hpp"

using namespace fluidbed;
using namespace fluidbed::render;
using namespace fluidbed::testing;

namespace {

constexpr int kW = 480, kH = 360;

class Render : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = make_context("osmesa", kW, kH);
    renderer_ = std::make_unique<Renderer>(*context_, std::string(FLUIDBED_ASSET_DIR) +
                                                          "/fonts/DejaVuSans.ttf");
  }
  static void TearDownTestSuite() {
    renderer_.reset();
    context_.reset();
  }
  // Settings without the close-up panel, so that frame_layout(s, w, h) places the one bed.
  static RenderSettings plain() {
    RenderSettings rs;
    rs.close_up = 0.0;
    return rs;
  }
  static Image draw(const Snapshot& s, const RenderSettings& rs = plain(), int w = kW, int h = kH) {
    return renderer_->render_frame(s, rs, w, h);
  }
  static std::unique_ptr<GlContext> context_;
  static std::unique_ptr<Renderer> renderer_;
};
std::unique_ptr<GlContext> Render::context_;
std::unique_ptr<Renderer> Render::renderer_;

}  // namespace

TEST_F(Render, ContextIsCoreProfileThreeThreeOrLater) {
  const std::string v = context_->version_string();
  EXPECT_NE(v.find("Core Profile"), std::string::npos) << v;
  GLint major = 0, minor = 0;
  context_->gl().GetIntegerv(GL_MAJOR_VERSION, &major);
  context_->gl().GetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33) << v;
}

TEST_F(Render, ImageHasTheAskedSize) {
  Snapshot s = empty_box();
  add_particle(s, {0.05, 0.05, 0.005});
  for (const auto& [w, h] : {std::pair{333, 222}, std::pair{1280, 720}, std::pair{200, 500}}) {
    const Image img = draw(s, {}, w, h);
    EXPECT_EQ(img.width, w);
    EXPECT_EQ(img.height, h);
    EXPECT_EQ(img.rgb.size(), static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
  }
}

// One particle of radius 1 cm in a 10 cm box (about 30 px across), its value half-way (or at a
// known fraction) up the quantity's range: the centre pixel has the colour map's colour there; a
// ring inside the disc is drawn on; a ring outside it is the bed's white.
struct ModeCase {
  ColourBy mode;
  ParticleState particle;
  double fraction;  // where the value sits on the colour scale
};

// Names the case in test output (instead of its bytes).
void PrintTo(const ModeCase& c, std::ostream* os) { *os << to_string(c.mode); }

class RenderModes : public Render, public ::testing::WithParamInterface<ModeCase> {};

TEST_P(RenderModes, ParticleLandsOnItsPixelsInTheColourMapColour) {
  const ModeCase& c = GetParam();
  Snapshot s = empty_box();
  add_particle(s, c.particle);
  // A second, small particle far away sets the top of the height range (0.08 m).
  add_particle(s, {0.09, 0.09, 0.001, 0, 0, 0, 0, 0, 0, 0.08});
  RenderSettings rs = plain();
  rs.colour_by = c.mode;
  rs.height_bands = 8;
  const Image img = draw(s, rs);
  const BedView bed = frame_layout(s, kW, kH).beds.front();
  const float cx = bed.px(c.particle.x), cy = bed.py(c.particle.y);
  const auto r = static_cast<float>(c.particle.r * bed.scale);
  ASSERT_GT(r, 10.0f);
  const Rgb want = c.mode == ColourBy::fixed ? rs.fixed_colour : colour_at(ColourMap::viridis, c.fraction);
  EXPECT_TRUE(near(at(img, cx, cy), to8(want), 2));
  for (const auto& [dx, dy] : {std::pair{1.0f, 0.0f}, {-1.0f, 0.0f}, {0.0f, 1.0f}, {0.0f, -1.0f}}) {
    // Inside: the same colour, shaded darker towards the rim (at most 45 % at the very edge).
    const Rgb8 in = at(img, cx + 0.6f * r * dx, cy + 0.6f * r * dy);
    const Rgb8 centre = to8(want);
    EXPECT_LE(in.r, centre.r + 1);
    EXPECT_GE(in.r, centre.r * 0.75 - 1);
    EXPECT_GE(in.g, centre.g * 0.75 - 1);
    EXPECT_GE(in.b, centre.b * 0.75 - 1);
    EXPECT_TRUE(is_background(at(img, cx + 1.2f * r * dx + 1.0f, cy + 1.2f * r * dy + 1.0f)));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Modes, RenderModes,
    ::testing::Values(
        ModeCase{ColourBy::speed, {0.04, 0.05, 0.01, 0.6, 0.8}, 1.0 / 1.5},
        // Force and torque on four decades: 0.35 N = 5000 x 7e-5 N, 7.5e-5 N m = 2500 x 3e-8.
        ModeCase{ColourBy::force, {0.04, 0.05, 0.01, 0, 0, 0.21, 0.28}, std::log10(5000.0) / 4},
        ModeCase{ColourBy::torque, {0.04, 0.05, 0.01, 0, 0, 0, 0, -0.75e-4},
                 std::log10(2500.0) / 4},
        ModeCase{ColourBy::overlap, {0.04, 0.05, 0.01, 0, 0, 0, 0, 0, 0.0075}, 0.75},
        // Height 0.03 of 0.08 m in 8 bands: band 3, drawn at its centre 3.5 / 8.
        ModeCase{ColourBy::height, {0.04, 0.05, 0.01, 0, 0, 0, 0, 0, 0, 0.03}, 3.5 / 8.0},
        // A monolayer has no z: every centre on the mid-plane, the middle of the depth scale.
        ModeCase{ColourBy::depth, {0.04, 0.05, 0.01}, 0.5},
        ModeCase{ColourBy::fixed, {0.04, 0.05, 0.01}, 0.0}),
    [](const auto& param_info) { return to_string(param_info.param.mode); });

// A gas arrow of the reference speed (one cell height long) in one cell, centred on the cell's
// centre: the shaft covers the centre and both halves along the arrow; the head's wide part is on
// the side it points to, and nothing is drawn across the tail.
// The fault: the arrows' reference was 10 m/s whatever the scene, so van Wachem's bed (0.9 m/s)
// showed dots. Three times the scene's velocity, rounded up to 1, 2 or 5 x 10^k.
TEST(GasArrows, ReferenceFollowsTheScenesVelocity) {
  EXPECT_DOUBLE_EQ(render::gas_arrow_reference_for(2.8), 10.0);  // the paper's bed, as before
  EXPECT_DOUBLE_EQ(render::gas_arrow_reference_for(0.9), 5.0);   // van Wachem's
  EXPECT_DOUBLE_EQ(render::gas_arrow_reference_for(0.3), 1.0);
  EXPECT_DOUBLE_EQ(render::gas_arrow_reference_for(0.5), 2.0);
  EXPECT_DOUBLE_EQ(render::gas_arrow_reference_for(20.0), 100.0);
  EXPECT_DOUBLE_EQ(render::gas_arrow_reference_for(0.0), 10.0);  // no gas
}

TEST_F(Render, GasArrowOfKnownDirectionCoversTheExpectedPixels) {
  for (const auto& [ux, uy] : {std::pair{10.0, 0.0}, {0.0, 10.0}, {-10.0, 0.0}}) {
    Snapshot s = empty_box();
    add_gas(s, 5, 5);
    const std::size_t cell = 2 * 5 + 2;
    s.gas_ux[cell] = ux;
    s.gas_uy[cell] = uy;
    const Image img = draw(s);
    const BedView bed = frame_layout(s, kW, kH).beds.front();
    const float cx = bed.px(0.05), cy = bed.py(0.05);
    const auto len = static_cast<float>(0.02 * bed.scale);  // one cell height
    ASSERT_GT(len, 30.0f);
    // Unit vectors along the arrow and across it, in pixels (y down).
    const auto ax = static_cast<float>(ux / 10.0), ay = static_cast<float>(-uy / 10.0);
    const float nx = -ay, ny = ax;
    auto px = [&](float along, float across) {
      return at(img, cx + ax * along * len + nx * across * len,
                cy + ay * along * len + ny * across * len);
    };
    EXPECT_TRUE(is_ink(px(0.0f, 0.0f))) << ux << ", " << uy;
    EXPECT_TRUE(is_ink(px(-0.35f, 0.0f)));
    EXPECT_TRUE(is_ink(px(0.2f, 0.0f)));
    // 0.2 of the length from the tip: inside the head's triangle, off the shaft.
    EXPECT_TRUE(is_ink(px(0.3f, 0.05f)));
    EXPECT_TRUE(is_ink(px(0.3f, -0.05f)));
    // The same offset at the tail is white, as is everything beyond the ends and to the sides.
    EXPECT_TRUE(is_background(px(-0.3f, 0.05f)));
    EXPECT_TRUE(is_background(px(-0.3f, -0.05f)));
    EXPECT_TRUE(is_background(px(0.62f, 0.0f)));
    EXPECT_TRUE(is_background(px(-0.62f, 0.0f)));
    EXPECT_TRUE(is_background(px(0.0f, 0.3f)));
    EXPECT_TRUE(is_background(px(0.0f, -0.3f)));
  }
}

// A particle moving at the reference speed along +x: its arrow starts at the centre and is three
// diameters long, so it sticks out on the right of the disc only.
TEST_F(Render, ParticleArrowPointsTheParticlesWay) {
  Snapshot s = empty_box();
  add_particle(s, {0.04, 0.05, 0.002, 1.0, 0.0});
  RenderSettings rs = plain();
  rs.particle_arrows = true;
  const Image img = draw(s, rs);
  const BedView bed = frame_layout(s, kW, kH).beds.front();
  const float cx = bed.px(0.04), cy = bed.py(0.05);
  const auto d = static_cast<float>(0.004 * bed.scale);
  EXPECT_TRUE(is_ink(at(img, cx + 1.5f * d, cy)));
  EXPECT_TRUE(is_ink(at(img, cx + 2.5f * d, cy)));
  EXPECT_TRUE(is_background(at(img, cx + 3.5f * d, cy)));
  EXPECT_TRUE(is_background(at(img, cx - 1.5f * d, cy)));
}

// The colour bar: the colour map from the bottom (low) to the top (high), ticks labelled beside it.
TEST_F(Render, ColourBarIsThere) {
  Snapshot s = empty_box();
  add_particle(s, {0.05, 0.05, 0.005});
  const Image img = draw(s);
  const Rect bar = frame_layout(s, kW, kH).colour_bar;
  const float x = 0.5f * (bar.x0 + bar.x1);
  for (double t : {0.1, 0.5, 0.9}) {
    const float y = bar.y1 - static_cast<float>(t) * bar.height();
    EXPECT_TRUE(near(at(img, x, y), to8(colour_at(ColourMap::viridis, t)), 6)) << t;
  }
  // Tick labels: dark text right of the bar.
  int ink = 0;
  for (int y = static_cast<int>(bar.y0) - 4; y < static_cast<int>(bar.y1) + 4; ++y)
    for (int xx = static_cast<int>(bar.x1) + 2; xx < static_cast<int>(bar.x1) + 60; ++xx)
      ink += is_ink(at(img, static_cast<float>(xx), static_cast<float>(y))) ? 1 : 0;
  EXPECT_GT(ink, 40);
  // The title and the time are written above it.
  int text = 0;
  for (int y = 0; y < static_cast<int>(bar.y0); ++y)
    for (int xx = static_cast<int>(bar.x0); xx < kW; ++xx)
      text += is_ink(at(img, static_cast<float>(xx), static_cast<float>(y))) ? 1 : 0;
  EXPECT_GT(text, 200);
}

TEST_F(Render, SameSnapshotGivesTheSamePixelsTwice) {
  Snapshot s = empty_box();
  add_gas(s, 5, 5);
  for (std::size_t c = 0; c < s.gas_ux.size(); ++c) {
    s.gas_ux[c] = 0.5 * static_cast<double>(c % 5) - 1.0;
    s.gas_uy[c] = 3.0 + 0.2 * static_cast<double>(c);
    s.porosity[c] = 0.4 + 0.02 * static_cast<double>(c);
  }
  for (int i = 0; i < 40; ++i)
    add_particle(s, {0.01 + 0.002 * i, 0.02 + 0.0015 * i, 0.002, 0.03 * i, -0.02 * i});
  RenderSettings rs = plain();
  rs.particle_arrows = true;
  rs.porosity_background = true;
  rs.close_up = 0.4;
  const Image a = draw(s, rs);
  const Image b = draw(s, rs);
  EXPECT_EQ(a.rgb, b.rgb);
  Renderer other(*context_, std::string(FLUIDBED_ASSET_DIR) + "/fonts/DejaVuSans.ttf");
  EXPECT_EQ(other.render_frame(s, rs, kW, kH).rgb, a.rgb);
}

// The walls are drawn and the bottom wall has a gap at the jet slot.
TEST_F(Render, WallsAndJetSlot) {
  Snapshot s = empty_box();
  const FrameLayout l = frame_layout(s, kW, kH);
  const Image img = draw(s);
  const BedView& bed = l.beds.front();
  const float wall_y = bed.inside.y1 + 0.5f * l.wall;
  const Rgb8 wall = at(img, bed.px(0.02), wall_y);
  EXPECT_TRUE(is_ink(wall));
  EXPECT_TRUE(is_ink(at(img, bed.inside.x0 - 0.5f * l.wall, bed.py(0.05))));
  EXPECT_TRUE(is_ink(at(img, bed.inside.x1 + 0.5f * l.wall, bed.py(0.05))));
  // In the slot (1 cm wide at the centre) the wall's grey is missing; the jet's blue arrow is there.
  const Rgb8 slot = at(img, bed.px(0.05) + 0.5f * 0.01f * static_cast<float>(bed.scale) - 3.0f, wall_y);
  EXPECT_FALSE(near(slot, wall, 20));
  const Rgb8 jet = at(img, bed.px(0.05), wall_y + 6.0f);
  EXPECT_GT(jet.b, jet.r + 80);
}

// The close-up: the bed's lower 40 % magnified beside it. A particle low in the bed appears in
// both panels in its colour, larger in the close-up; one above the close-up's window appears only
// in the whole bed.
TEST_F(Render, CloseUpMagnifiesTheLowerBed) {
  Snapshot s = empty_box(0.15, 0.9);
  add_particle(s, {0.05, 0.1, 0.004});
  add_particle(s, {0.10, 0.37, 0.004});  // just above the close-up's window (0 to 0.36 m)
  RenderSettings rs = plain();
  rs.close_up = 0.4;
  const Image img = draw(s, rs, 1280, 720);
  const FrameLayout l = frame_layout(s, 1280, 720, 0.4);
  ASSERT_EQ(l.beds.size(), 2u);
  const BedView& whole = l.beds[0];
  const BedView& zoom = l.beds[1];
  EXPECT_GT(zoom.scale, 2.0 * whole.scale);
  EXPECT_NEAR(zoom.inside.height(), static_cast<float>(0.36 * zoom.scale), 1.0f);
  EXPECT_GT(zoom.inside.x0, whole.inside.x1);
  const Rgb8 still = to8(colour_at(ColourMap::viridis, 0.0));
  EXPECT_TRUE(near(at(img, whole.px(0.05), whole.py(0.1)), still, 2));
  EXPECT_TRUE(near(at(img, zoom.px(0.05), zoom.py(0.1)), still, 2));
  // Magnified: 0.8 radii from the centre is on the disc in the close-up; 1.6 radii from it is
  // white in the whole bed.
  EXPECT_TRUE(is_ink(at(img, zoom.px(0.05 + 0.8 * 0.004), zoom.py(0.1))));
  EXPECT_TRUE(is_background(at(img, whole.px(0.05 + 1.6 * 0.004) + 1.0f, whole.py(0.1))));
  EXPECT_TRUE(near(at(img, whole.px(0.10), whole.py(0.37)), still, 2));
  // Where the high particle would be in the close-up's scale, above its window: not drawn.
  const Rgb8 above = at(img, zoom.px(0.10), zoom.py(0.37));
  EXPECT_FALSE(near(above, still, 40));
}

TEST_F(Render, PorosityBackgroundDarkerWhereDense) {
  Snapshot s = empty_box();
  add_gas(s, 5, 5);
  s.porosity[0] = 0.4;  // bottom-left cell
  RenderSettings rs = plain();
  rs.gas_arrows = false;
  rs.porosity_background = true;
  const Image img = draw(s, rs);
  const BedView bed = frame_layout(s, kW, kH).beds.front();
  const Rgb8 dense = at(img, bed.px(0.01), bed.py(0.01));
  const Rgb8 open = at(img, bed.px(0.05), bed.py(0.05));
  EXPECT_LT(dense.r + dense.g + dense.b + 100, open.r + open.g + open.b);
  rs.porosity_background = false;
  EXPECT_TRUE(is_background(at(draw(s, rs), bed.px(0.01), bed.py(0.01))));
}

// Bubble outlines: the edges the snapshot carries are drawn in red where the toggle is on, and
// nothing of them where it is off.
TEST_F(Render, BubbleOutlinesDrawnWhereTheSnapshotsEdgesAre) {
  Snapshot s = empty_box();
  // A square outline 20 mm wide around (0.05, 0.05).
  s.bubble_edges = {0.04f, 0.04f, 0.06f, 0.04f, 0.06f, 0.04f, 0.06f, 0.06f,
                    0.06f, 0.06f, 0.04f, 0.06f, 0.04f, 0.06f, 0.04f, 0.04f};
  RenderSettings rs = plain();
  rs.gas_arrows = false;
  rs.bubble_outlines = true;
  const Image on = draw(s, rs);
  const BedView bed = frame_layout(s, kW, kH).beds.front();
  for (const auto& [x, y] : {std::pair{0.05, 0.04}, {0.06, 0.05}, {0.05, 0.06}, {0.04, 0.05}}) {
    const Rgb8 c = at(on, bed.px(x), bed.py(y));
    EXPECT_GT(c.r, c.g + 100) << x << ", " << y;
    EXPECT_GT(c.r, c.b + 100) << x << ", " << y;
  }
  EXPECT_TRUE(is_background(at(on, bed.px(0.05), bed.py(0.05))));  // inside: not filled
  rs.bubble_outlines = false;
  EXPECT_TRUE(is_background(at(draw(s, rs), bed.px(0.05), bed.py(0.04))));
}

// A montage: each snapshot in its own panel, at the place montage_layout gives.
TEST_F(Render, MontagePutsEachSnapshotInItsPanel) {
  std::vector<Snapshot> snaps;
  for (int k = 0; k < 3; ++k) {
    Snapshot s = empty_box(0.05, 0.2);
    s.time = 0.2 * (k + 1);
    add_particle(s, {0.025, 0.03 + 0.05 * k, 0.01, 0.0, 0.0});
    snaps.push_back(s);
  }
  const std::vector<const Snapshot*> ptrs{&snaps[0], &snaps[1], &snaps[2]};
  const Image img = renderer_->render_montage(ptrs, {}, 400);
  const FrameLayout l = montage_layout(snaps[0], 3, 400);
  EXPECT_EQ(img.width, l.width);
  EXPECT_EQ(img.height, 400);
  const Rgb8 still = to8(colour_at(ColourMap::viridis, 0.0));
  for (int k = 0; k < 3; ++k) {
    const BedView& bed = l.beds[static_cast<std::size_t>(k)];
    EXPECT_TRUE(near(at(img, bed.px(0.025), bed.py(0.03 + 0.05 * k)), still, 2)) << k;
    // Where the other panels have their particle, this one is empty.
    EXPECT_TRUE(is_background(at(img, bed.px(0.025), bed.py(0.03 + 0.05 * ((k + 1) % 3)))));
  }
}

// A thick bed seen through the front wall. Two spheres overlap on the picture: the front one
// (z = r, full brightness, the colour map's low end) covers the back one (z = thickness - r, the
// high end at 60 %) whichever comes first in the arrays; a third, alone at the back, shows the
// depth shade at its centre.
TEST_F(Render, ThickBedShowsTheFrontSphereWhereSpheresOverlap) {
  const ParticleState front{0.04, 0.05, 0.01};
  const ParticleState back{0.047, 0.05, 0.01, 1.5, 0.0};  // covers the front one's centre
  const ParticleState alone{0.08, 0.05, 0.01, 1.5, 0.0};
  const Rgb low = colour_at(ColourMap::viridis, 0.0), high = colour_at(ColourMap::viridis, 1.0);
  const Rgb dim{0.6f * high.r, 0.6f * high.g, 0.6f * high.b};
  for (const bool front_first : {true, false}) {
    Snapshot s = empty_box();
    s.thickness = 0.04;
    const auto add = [&s](const ParticleState& p, double z) {
      add_particle(s, p);
      s.z.push_back(z);
    };
    if (front_first) add(front, 0.01);
    add(back, 0.03);
    if (!front_first) add(front, 0.01);
    add(alone, 0.03);
    const Image img = draw(s);
    const BedView bed = frame_layout(s, kW, kH).beds.front();
    ASSERT_GT(0.007 * bed.scale, 10.0);
    EXPECT_TRUE(near(at(img, bed.px(front.x), bed.py(front.y)), to8(low), 2)) << front_first;
    EXPECT_TRUE(near(at(img, bed.px(alone.x), bed.py(alone.y)), to8(dim), 2)) << front_first;
    // The back sphere shows beyond the front one's rim, no brighter than its dimmed centre.
    const Rgb8 behind = at(img, bed.px(0.0555), bed.py(0.05));
    EXPECT_TRUE(is_ink(behind));
    EXPECT_LE(behind.g, to8(dim).g + 1);
    EXPECT_GT(behind.g, to8(low).g + 30);
  }
}

// The depth mode spans the slab: the front wall (z = 0) is the colour map's low end, the back
// wall (z = thickness) its high end (drawn at the back's 60 % shade).
TEST_F(Render, DepthModeSpansTheSlabFromFrontToBack) {
  Snapshot s = empty_box();
  s.thickness = 0.04;
  add_particle(s, {0.03, 0.05, 0.01});
  s.z.push_back(0.0);
  add_particle(s, {0.07, 0.05, 0.01});
  s.z.push_back(0.04);
  RenderSettings rs = plain();
  rs.colour_by = ColourBy::depth;
  const ColourScale scale = colour_scale(ColourBy::depth, s, 0.0, 0.0, 8);
  EXPECT_EQ(scale.bands, 0);
  EXPECT_DOUBLE_EQ(scale_position(scale, particle_value(ColourBy::depth, s, 0)), 0.0);
  EXPECT_DOUBLE_EQ(scale_position(scale, particle_value(ColourBy::depth, s, 1)), 1.0);
  EXPECT_DOUBLE_EQ(depth_shade(s, 0), 1.0);
  EXPECT_DOUBLE_EQ(depth_shade(s, 1), kBackShade);
  const Image img = draw(s, rs);
  const BedView bed = frame_layout(s, kW, kH).beds.front();
  const Rgb high = colour_at(ColourMap::viridis, 1.0);
  const auto back = static_cast<float>(kBackShade);
  EXPECT_TRUE(near(at(img, bed.px(0.03), bed.py(0.05)), to8(colour_at(ColourMap::viridis, 0.0)), 2));
  EXPECT_TRUE(near(at(img, bed.px(0.07), bed.py(0.05)),
                   to8({back * high.r, back * high.g, back * high.b}), 2));
  // Half-way across the slab: the middle of both the colour map and the shade.
  s.z[1] = 0.02;
  EXPECT_DOUBLE_EQ(scale_position(scale, particle_value(ColourBy::depth, s, 1)), 0.5);
  EXPECT_DOUBLE_EQ(depth_shade(s, 1), 0.5 * (1.0 + kBackShade));
}

// Speed, force and torque colours are magnitudes: in the plane for a monolayer, in three
// dimensions for a thick bed (3-4-12 triangles: |(3, 4)| = 5, |(3, 4, 12)| = 13).
TEST(ColourModes, MagnitudesCountTheSlabsPartsInAThickBed) {
  Snapshot s = empty_box();
  add_particle(s, {0.03, 0.05, 0.002, 3.0, 4.0, 0.3, 0.4, 4e-5});
  EXPECT_DOUBLE_EQ(particle_value(ColourBy::speed, s, 0), 5.0);
  EXPECT_DOUBLE_EQ(particle_value(ColourBy::force, s, 0), 0.5);
  EXPECT_DOUBLE_EQ(particle_value(ColourBy::torque, s, 0), 4e-5);
  s.thickness = 0.02;
  s.z = {0.01};
  s.vz = {12.0};
  s.fz = {1.2};
  s.torque_x = {3e-5};
  s.torque_y = {12e-5};
  EXPECT_DOUBLE_EQ(particle_value(ColourBy::speed, s, 0), 13.0);
  EXPECT_DOUBLE_EQ(particle_value(ColourBy::force, s, 0), 1.3);
  EXPECT_NEAR(particle_value(ColourBy::torque, s, 0), 13e-5, 1e-19);
}

// The fault: force and torque on a linear range drew nearly every sphere of the paper's bed in
// the darkest colour (0.7 N is set by a few impacts; a resting sphere carries about its weight,
// 9e-4 N). On four decades a resting sphere sits a quarter up the map, an impact near its top,
// and a sphere without contact or torque at the bottom; a range from 0 given by hand is linear.
TEST(ColourModes, ForceAndTorqueAreLogarithmicOverFourDecades) {
  const Snapshot s = empty_box();
  const ColourScale force = colour_scale(ColourBy::force, s, 0.0, 0.0, 8);
  EXPECT_TRUE(force.log);
  EXPECT_EQ(force.title, "force (N, log scale)");
  const double weight = 2700.0 * 9.81 * 4.0 / 3.0 * M_PI * std::pow(0.002, 3);  // 8.9e-4 N
  EXPECT_NEAR(scale_position(force, weight), std::log10(weight / 7e-5) / 4.0, 1e-12);
  EXPECT_GT(scale_position(force, weight), 0.25);
  EXPECT_NEAR(scale_position(force, 0.07), 0.75, 1e-12);
  EXPECT_DOUBLE_EQ(scale_position(force, 0.7), 1.0);
  EXPECT_DOUBLE_EQ(scale_position(force, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(scale_position(force, 1e-9), 0.0);
  EXPECT_DOUBLE_EQ(scale_position(force, 5.0), 1.0);
  for (double t : {0.0, 0.3, 0.5, 1.0})
    EXPECT_NEAR(scale_position(force, scale_value(force, t)), t, 1e-12);

  const ColourScale torque = colour_scale(ColourBy::torque, s, 0.0, 0.0, 8);
  EXPECT_TRUE(torque.log);
  EXPECT_EQ(torque.title, "torque (N m, log scale)");
  EXPECT_NEAR(scale_position(torque, 3e-6), 0.5, 1e-12);

  // A range set by hand: logarithmic above zero, linear from zero.
  const ColourScale above = colour_scale(ColourBy::force, s, 1e-3, 1.0, 8);
  EXPECT_TRUE(above.log);
  EXPECT_NEAR(scale_position(above, 0.1), 2.0 / 3.0, 1e-12);
  const ColourScale from_zero = colour_scale(ColourBy::force, s, 0.0, 0.7, 8);
  EXPECT_FALSE(from_zero.log);
  EXPECT_EQ(from_zero.title, "force (N)");
  EXPECT_DOUBLE_EQ(scale_position(from_zero, 0.35), 0.5);
  EXPECT_DOUBLE_EQ(scale_value(from_zero, 0.5), 0.35);
  // Other quantities stay linear.
  EXPECT_FALSE(colour_scale(ColourBy::speed, s, 0.0, 0.0, 8).log);
  EXPECT_FALSE(colour_scale(ColourBy::speed, s, 0.5, 1.0, 8).log);
}

// The fault: a 1000 x 650 window dropped the close-up though both panels fitted with the beds
// 75 % as tall as the whole bed alone. The paper's and the teaching bed's domain (0.15 x 0.9 m)
// in the area the viewer's panel leaves (panel_layout: 450 px of 1000, 450 of 1280, 600 of 1920,
// 360 of 800): kept at 1000 x 650, 1280 x 720 and 1920 x 1080, dropped at 800 x 650 where the
// beds would be 38 % as tall.
TEST(Layout, TheCloseUpStaysWhileTheBedsKeepTwoThirdsOfTheirHeight) {
  const Snapshot s = empty_box(0.15, 0.9);
  EXPECT_TRUE(keeps_close_up(s, 1000 - 450, 650, 0.4, true));
  EXPECT_TRUE(keeps_close_up(s, 1280 - 450, 720, 0.4, true));
  EXPECT_TRUE(keeps_close_up(s, 1920 - 600, 1080, 0.4, true));
  EXPECT_FALSE(keeps_close_up(s, 800 - 360, 650, 0.4, true));
  const double both = frame_layout(s, 550, 650, 0.4, true).beds.front().scale;
  const double alone = frame_layout(s, 550, 650, 0.0, true).beds.front().scale;
  EXPECT_GT(both / alone, 0.7);
  EXPECT_LT(both / alone, 0.8);  // what the old rule needed
  EXPECT_FALSE(keeps_close_up(s, 550, 650, 0.0, true));  // none asked for
}

TEST(RenderBackends, UnknownNameListsTheKnownOnes) {
  try {
    make_context("vulkan", 64, 64);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("vulkan"), std::string::npos) << m;
    EXPECT_NE(m.find("osmesa"), std::string::npos) << m;
    EXPECT_NE(m.find("glfw"), std::string::npos) << m;
  }
  try {
    parse_colour_by("temperature");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("speed"), std::string::npos) << m;
    EXPECT_NE(m.find("torque"), std::string::npos) << m;
  }
}

TEST(RenderBackends, WindowWithoutDisplaySaysSo) {
  if (std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY")) GTEST_SKIP() << "a display exists";
  try {
    make_context("glfw", 64, 64);
    FAIL() << "a window without a display";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("osmesa"), std::string::npos) << e.what();
  }
}

TEST(ColourMaps, ViridisEndsAndMiddleAsPublished) {
  EXPECT_TRUE(near(to8(colour_at(ColourMap::viridis, 0.0)), {68, 1, 84}, 1));
  EXPECT_TRUE(near(to8(colour_at(ColourMap::viridis, 1.0)), {253, 231, 37}, 1));
  EXPECT_TRUE(near(to8(colour_at(ColourMap::viridis, 128.0 / 255.0)), {33, 145, 140}, 1));
  // Lightness rises monotonically (a perceptual map): check the luma of 64 samples.
  double last = -1.0;
  for (int k = 0; k <= 64; ++k) {
    const Rgb c = colour_at(ColourMap::viridis, k / 64.0);
    const double luma = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    EXPECT_GT(luma, last) << k;
    last = luma;
  }
}

// The window backend where a display exists (ctest runs this under xvfb-run, with
// FLUIDBED_REQUIRE_DISPLAY set): a core-profile window whose frame matches the offscreen one
// pixel for pixel (both are Mesa's llvmpipe), in the same process as an OSMesa context.
TEST(GlfwWindow, DrawsTheSameFrameAsOffscreen) {
  if (!std::getenv("DISPLAY")) {
    if (std::getenv("FLUIDBED_REQUIRE_DISPLAY")) FAIL() << "DISPLAY is not set";
    GTEST_SKIP() << "no display (ctest runs this test under xvfb-run)";
  }
  const std::string font = std::string(FLUIDBED_ASSET_DIR) + "/fonts/DejaVuSans.ttf";
  Snapshot s = empty_box();
  add_gas(s, 5, 5);
  s.gas_uy.assign(s.gas_uy.size(), 4.0);
  for (int i = 0; i < 20; ++i) add_particle(s, {0.01 + 0.004 * i, 0.03, 0.002, 0.05 * i, 0.0});
  Image offscreen;
  {
    auto ctx = make_context("osmesa", 320, 240);
    Renderer r(*ctx, font);
    offscreen = r.render_frame(s, {}, 320, 240);
  }
  auto window = make_context("glfw", 320, 240);
  EXPECT_EQ(window->name(), "glfw");
  EXPECT_NE(window->version_string().find("Core Profile"), std::string::npos)
      << window->version_string();
  Renderer r(*window, font);
  const Image img = r.render_frame(s, {}, 320, 240);
  r.blit_to_default(window->width(), window->height());
  window->present();
  ASSERT_EQ(img.rgb.size(), offscreen.rgb.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < img.rgb.size(); ++k)
    differ += std::abs(int{img.rgb[k]} - int{offscreen.rgb[k]}) > 2 ? 1 : 0;
  EXPECT_LT(differ, img.rgb.size() / 1000) << differ << " of " << img.rgb.size() << " values differ";
}

// PNG files decode (stb_image, an independent reader) to exactly the pixels written.
TEST(Png, WritesWhatReadsBack) {
  Image img;
  img.width = 37;
  img.height = 23;
  img.rgb.resize(37 * 23 * 3);
  for (std::size_t k = 0; k < img.rgb.size(); ++k)
    img.rgb[k] = static_cast<std::uint8_t>((k * 7919u + (k >> 5) * 31u) & 0xFF);
  const auto path = temp_dir("png") / "t.png";
  write_png(path.string(), img);
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &w, &h, &n, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 23);
  EXPECT_EQ(n, 3);
  EXPECT_TRUE(std::equal(img.rgb.begin(), img.rgb.end(), data));
  stbi_image_free(data);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".part"));
}

// stb_truetype gives a code point the font lacks the box of the first missing one by its index in
// another range, reading past the end of a shorter range (ASan found it). Every code point the
// atlas holds must have a glyph in the shipped font.
TEST(FontAtlasGlyphs, EveryCodePointTheAtlasHoldsIsInTheFont) {
  const FontFile f = load_font({std::string(FLUIDBED_ASSET_DIR) + "/fonts/DejaVuSans.ttf"});
  stbtt_fontinfo info;
  ASSERT_NE(stbtt_InitFont(&info, f.bytes.data(), f.offset), 0);
  const std::vector<int> cps = atlas_code_points();
  EXPECT_GT(cps.size(), 200u);
  for (int cp : cps) EXPECT_NE(stbtt_FindGlyphIndex(&info, cp), 0) << "U+" << std::hex << cp;
  // The characters the labels use are there: degree, times, Delta, eta, superscript minus, minus.
  for (int cp : {0xB0, 0xD7, 0x394, 0x3B7, 0x207B, 0x2212})
    EXPECT_NE(std::find(cps.begin(), cps.end(), cp), cps.end()) << "U+" << std::hex << cp;
}
