// The viewer: picking geometry (no GL), `fluidbed view` in scripted mode in a window (under
// xvfb-run: ctest's ViewWindowUnderXvfb), its headless fallback, and its bad-input errors.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/wait.h>
#include "../view/view_scene.hpp"
#include "render/picking.hpp"
#include "render_support.hpp"
#include "view_support.hpp"

namespace fluidbed::testing {
namespace {

// ---------------------------------------------------------------------------------------------
// Geometry.

// A zoomed bed panel keeps its place (its clip) and shows the chosen point at its centre; the
// view never leaves the bed; picking sees through the zoom.
TEST(ViewPicking, ZoomMagnifiesOnePanelAboutAPoint) {
  Snapshot s = empty_box(0.1, 0.2);
  add_particle(s, {0.02, 0.03, 0.002});
  const render::FrameLayout plain = render::frame_layout(s, 800, 600, 0.4);
  render::FrameLayout l = plain;
  render::zoom_bed(l, {1, 2.0, 0.03, 0.04});
  const render::BedView& z = l.beds[1];
  EXPECT_TRUE(z.zoomed);
  EXPECT_FALSE(l.beds[0].zoomed);
  EXPECT_NEAR(z.scale, 2.0 * plain.beds[1].scale, 1e-9);
  EXPECT_EQ(z.clip.x0, plain.beds[1].clip.x0);  // the panel stays where it was
  EXPECT_EQ(z.clip.y1, plain.beds[1].clip.y1);
  const float cx = 0.5f * (plain.beds[1].inside.x0 + plain.beds[1].inside.x1);
  const float cy = 0.5f * (plain.beds[1].inside.y0 + plain.beds[1].inside.y1);
  EXPECT_NEAR(z.px(0.03), cx, 1e-3);
  EXPECT_NEAR(z.py(0.04), cy, 1e-3);
  double x = 0, y = 0;
  ASSERT_TRUE(render::frame_to_world(l, cx, cy, x, y));
  EXPECT_NEAR(x, 0.03, 1e-6);
  EXPECT_NEAR(y, 0.04, 1e-6);
  EXPECT_EQ(render::bed_at(l, cx, cy), 1);
  // The particle at (0.02, 0.03) is picked where the zoomed panel draws it.
  EXPECT_EQ(render::pick_particle(s, l, z.px(0.02), z.py(0.03)), std::optional<std::size_t>(0));
  // About a corner: the view stops at the bed's walls.
  render::FrameLayout c = plain;
  render::zoom_bed(c, {1, 4.0, 0.0, 0.0});
  EXPECT_NEAR(c.beds[1].inside.x0, plain.beds[1].inside.x0, 1e-3);
  EXPECT_NEAR(c.beds[1].inside.y1, plain.beds[1].inside.y1, 1e-3);
  // A zoom of 1, or of a panel that is not there, changes nothing.
  render::FrameLayout same = plain;
  render::zoom_bed(same, {0, 1.0, 0.05, 0.1});
  render::zoom_bed(same, {5, 3.0, 0.05, 0.1});
  EXPECT_EQ(same.beds[0].inside.x0, plain.beds[0].inside.x0);
  EXPECT_FALSE(same.beds[0].zoomed);
}

TEST(ViewPicking, FindsTheParticleDrawnUnderAPixel) {
  Snapshot s = empty_box(0.1, 0.2);
  add_particle(s, {0.02, 0.03, 0.002});
  add_particle(s, {0.0238, 0.03, 0.002});  // overlapping the first a little
  add_particle(s, {0.07, 0.15, 0.002});
  const render::FrameLayout l = render::frame_layout(s, 800, 600, 0.4);
  ASSERT_EQ(l.beds.size(), 2u);
  double fx = 0, fy = 0;
  render::world_to_frame(l, 0.07, 0.15, fx, fy);
  EXPECT_EQ(render::pick_particle(s, l, fx, fy), std::optional<std::size_t>(2));
  render::world_to_frame(l, 0.0205, 0.0302, fx, fy);
  EXPECT_EQ(render::pick_particle(s, l, fx, fy), std::optional<std::size_t>(0));  // nearer centre
  render::world_to_frame(l, 0.05, 0.1, fx, fy);
  EXPECT_FALSE(render::pick_particle(s, l, fx, fy).has_value());
  // The close-up panel (the lower 40 % magnified) picks the same particle.
  const render::BedView& z = l.beds[1];
  EXPECT_EQ(render::pick_particle(s, l, z.px(0.0238), z.py(0.03)), std::optional<std::size_t>(1));
  double x = 0, y = 0;
  ASSERT_TRUE(render::frame_to_world(l, z.px(0.0238), z.py(0.03), x, y));
  EXPECT_NEAR(x, 0.0238, 1e-5);
  EXPECT_NEAR(y, 0.03, 1e-5);
}

// A thick bed: where spheres cover each other on the picture, the front-most (smallest z) is
// picked, though another's centre is nearer the pointer, whichever order the arrays have.
TEST(ViewPicking, ThickBedPicksTheFrontMostSphere) {
  for (const bool front_first : {true, false}) {
    Snapshot s = empty_box(0.1, 0.2);
    s.thickness = 0.02;
    const double xs[] = {0.0200, 0.0225, 0.0250}, zs[] = {0.004, 0.010, 0.016};  // front to back
    for (int k = 0; k < 3; ++k) {
      const int j = front_first ? k : 2 - k;
      add_particle(s, {xs[j], 0.03, 0.002});
      s.z.push_back(zs[j]);
    }
    const std::size_t front = front_first ? 0 : 2, middle = 1, back = 2 - front;
    const render::FrameLayout l = render::frame_layout(s, 800, 600, 0.4);
    double fx = 0, fy = 0;
    // Covered by the front and middle ones, nearer the middle one's centre.
    render::world_to_frame(l, 0.0215, 0.03, fx, fy);
    EXPECT_EQ(render::pick_particle(s, l, fx, fy), std::optional<std::size_t>(front)) << front_first;
    // Beyond the front one's rim, covered by the middle and back ones, nearer the back one's centre.
    render::world_to_frame(l, 0.0240, 0.03, fx, fy);
    EXPECT_EQ(render::pick_particle(s, l, fx, fy), std::optional<std::size_t>(middle)) << front_first;
    // The close-up picks the same.
    const render::BedView& z = l.beds[1];
    EXPECT_EQ(render::pick_particle(s, l, z.px(0.0215), z.py(0.03)), std::optional<std::size_t>(front));
    // Without depth (a monolayer) the nearest centre is picked, as before.
    s.z.clear();
    EXPECT_EQ(render::pick_particle(s, l, fx, fy), std::optional<std::size_t>(back)) << front_first;
  }
}

// In a thick bed spheres that overlap on the picture but lie apart in depth do not touch, and
// the front and back walls count.
TEST(ViewPicking, ThickBedContactsAreInThreeDimensions) {
  Snapshot s = empty_box(0.1, 0.2);
  s.thickness = 0.02;
  add_particle(s, {0.05, 0.05, 0.002});
  s.z.push_back(0.0019);  // touches the front wall
  add_particle(s, {0.0538, 0.05, 0.002});
  s.z.push_back(0.0019);  // 3.8 mm away at the same depth: overlaps the first
  add_particle(s, {0.0519, 0.05, 0.002});
  s.z.push_back(0.0080);  // on the picture over both, 6.1 mm behind: touches neither
  const render::ParticleContacts c = render::contacts_of(s, 0);
  EXPECT_EQ(c.walls, 1);
  ASSERT_EQ(c.particles.size(), 1u);
  EXPECT_EQ(c.particles[0], 1u);
  EXPECT_NEAR(c.max_overlap, 1.0 - 0.0038 / 0.004, 1e-9);
  EXPECT_EQ(render::contacts_of(s, 2).count(), 0u);
  s.z[2] = 0.0181;  // touches the back wall
  EXPECT_EQ(render::contacts_of(s, 2).walls, 1);
  // The same spheres in a monolayer: all three overlap on the mid-plane, no front or back wall.
  s.z.clear();
  EXPECT_EQ(render::contacts_of(s, 2).particles.size(), 2u);
  EXPECT_EQ(render::contacts_of(s, 0).walls, 0);
}

TEST(ViewPicking, ContactsAreOverlapsAndWalls) {
  Snapshot s = empty_box(0.1, 0.2);
  add_particle(s, {0.0019, 0.0019, 0.002});  // touches the left and bottom walls
  add_particle(s, {0.0057, 0.0019, 0.002});  // 3.8 mm away: overlaps the first
  add_particle(s, {0.0098, 0.0019, 0.002});  // 4.1 mm from the second: no contact
  const render::ParticleContacts c = render::contacts_of(s, 0);
  EXPECT_EQ(c.walls, 2);
  ASSERT_EQ(c.particles.size(), 1u);
  EXPECT_EQ(c.particles[0], 1u);
  EXPECT_NEAR(c.max_overlap, 1.0 - 0.0038 / 0.004, 1e-9);
  EXPECT_EQ(render::contacts_of(s, 2).count(), 1u);  // only the bottom wall
}

// ---------------------------------------------------------------------------------------------
// The program.

TEST(ViewWindow, ScriptedRunChangesTheGasAndTakesAScreenshot) {
  if (!std::getenv("DISPLAY")) {
    if (std::getenv("FLUIDBED_REQUIRE_DISPLAY")) FAIL() << "DISPLAY is not set";
    GTEST_SKIP() << "no display (ctest runs this test under xvfb-run)";
  }
  const auto dir = fresh_dir("window");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string shot0 = (dir / "start.png").string(), shot1 = (dir / "later.png").string();
  const std::string script = written_file(dir / "demo.txt", "screenshot " + shot0 +
                                                              "\n"
                                                              "at 0.01 velocity 3.5\n"
                                                              "colour mixing\n"
                                                              "track 40\n"
                                                              "at 0.02 screenshot " +
                                                              shot1 +
                                                              "\n"
                                                              "quit\n");
  const ViewRun r = run_view(
      dir, scene + " --script " + script + " --frame-size 960x600 --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("wrote " + shot1), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("frames/s"), std::string::npos) << r.output;
  const Png a = read_png(shot0), b = read_png(shot1);
  ASSERT_EQ(a.w, 960);
  ASSERT_EQ(a.h, 600);
  ASSERT_EQ(b.w, 960);
  // The panel: ImGui's dark window over the left 380 px (dark grey, light text on it).
  const auto dark = [](int r_, int g, int b_) { return r_ < 60 && g < 60 && b_ < 60; };
  const auto light = [](int r_, int g, int b_) { return r_ > 180 && g > 180 && b_ > 180; };
  EXPECT_GT(count_pixels(b, 0, 370, 0, 600, dark), 370 * 600 / 2);
  EXPECT_GT(count_pixels(b, 0, 370, 0, 120, light), 300);  // text: the title, buttons, time
  // The buttons are ImGui's blue.
  EXPECT_GT(count_pixels(b, 0, 370, 0, 80,
                         [](int r_, int g, int b_) { return b_ > r_ + 40 && b_ > 90 && g > 50; }),
            500);
  // The bed right of the panel: particles coloured by the mixing bands (viridis: purple to
  // yellow; green-yellow ones are the upper bands), on the light page.
  const auto viridis_yellow = [](int r_, int g, int b_) { return r_ > 150 && g > 170 && b_ < 110; };
  const auto viridis_purple = [](int r_, int g, int b_) {
    return r_ > 50 && r_ < 90 && b_ > 70 && g < 40;
  };
  EXPECT_GT(count_pixels(b, 380, 960, 0, 600, viridis_yellow), 200);
  EXPECT_GT(count_pixels(b, 380, 960, 0, 600, viridis_purple), 200);
  // At the start the colour was speed: the bed at rest is all the low end (no yellow particles
  // in the bed; the colour bars still hold some).
  EXPECT_GT(count_pixels(a, 380, 960, 0, 600, light), 960 * 600 / 4);
  // The velocity shows in the panel's slider and the frame's label: the two pictures differ.
  int differ = 0;
  for (std::size_t k = 0; k < a.rgb.size(); ++k) differ += a.rgb[k] != b.rgb[k] ? 1 : 0;
  EXPECT_GT(differ, 1000);
  // The tracked particle's red ring.
  EXPECT_GT(count_pixels(b, 380, 960, 0, 600,
                         [](int r_, int g, int b_) { return r_ > 190 && g < 70 && b_ < 70; }),
            20);
}

TEST(ViewWindow, RecordsAnMp4) {
  if (!std::getenv("DISPLAY")) {
    if (std::getenv("FLUIDBED_REQUIRE_DISPLAY")) FAIL() << "DISPLAY is not set";
    GTEST_SKIP() << "no display (ctest runs this test under xvfb-run)";
  }
  const auto dir = fresh_dir("record");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string video = (dir / "demo.mp4").string();
  const std::string script =
      written_file(dir / "rec.txt", "record " + video + "\nwait 1.0\nrecord stop\nquit\n");
  const ViewRun r = run_view(
      dir, scene + " --script " + script + " --frame-size 640x400 --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(std::filesystem::exists(video)) << r.output;
  EXPECT_GT(std::filesystem::file_size(video), 1000u);
}

TEST(ViewCommand, WithoutADisplayWritesHeadlessFrames) {
  const auto dir = fresh_dir("headless");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string shot = (dir / "shot.png").string();
  const std::string script = written_file(
      dir / "s.txt", "at 0.01 velocity 3\nat 0.02 screenshot " + shot + "\nat 0.04 quit\n");
  const ViewRun r = run_view(
      dir, scene + " --script " + script + " --frame-size 320x240 --out " + (dir / "out").string(),
      "env -u DISPLAY -u WAYLAND_DISPLAY");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.rfind("fluidbed view: no display", 0), 0u)
      << r.output;  // the first line says so
  EXPECT_TRUE(std::filesystem::exists(dir / "out/frames/frame_000000.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out/frames/frame_000001.png"));  // t = 0.04 s
  EXPECT_FALSE(std::filesystem::exists(dir / "out/frames/frame_000002.png"));
  const Png p = read_png(shot);
  EXPECT_EQ(p.w, 320);
}

// `view SCENE --umf`: the scene's U_mf and how it was found, then exit 0 without a window; the
// teaching bed's answer is the one shipped with the program (its packed bed is the fixture's). A
// bed without gas has none: one line, status 2.
TEST(ViewCommand, UmfPrintsTheScenesAnswerAndExits) {
  const auto dir = fresh_dir("umf");
  const ViewRun r = run_view(dir, std::string(FLUIDBED_ASSET_DIR) + "/scenes/teaching.toml --umf");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::size_t at = r.output.find("fluidbed view: U_mf = ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double umf = std::stod(r.output.substr(at + 22));
  EXPECT_NE(r.output.find("decreasing branch"), std::string::npos) << r.output;
  const std::size_t file_at = r.output.find("cached: ");
  ASSERT_NE(file_at, std::string::npos) << r.output;
  const std::string file =
      r.output.substr(file_at + 8, r.output.find(')', file_at) - file_at - 8);
  EXPECT_EQ(std::filesystem::path(file).parent_path(),
            std::filesystem::path(FLUIDBED_ASSET_DIR) / "umf")
      << file;
  std::ifstream in(file);
  std::string word;
  double shipped = 0.0;
  in >> word >> shipped;
  EXPECT_EQ(word, "umf_m_s") << file;
  EXPECT_NEAR(umf, shipped, 5e-4) << r.output;  // printed to 3 decimals
  const ViewRun none = run_view(dir, std::string(FLUIDBED_ASSET_DIR) + "/scenes/drop.toml --umf");
  EXPECT_EQ(none.status, 2) << none.output;
  EXPECT_NE(none.output.find("no gas"), std::string::npos) << none.output;
  EXPECT_EQ(std::count(none.output.begin(), none.output.end(), '\n'), 1) << none.output;
}

TEST(ViewCommand, BadInputIsOneLineAndStatusTwo) {
  const auto dir = fresh_dir("bad");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string bad_script = written_file(dir / "bad.txt", "velocity 2\nfly away\n");
  ViewRun r = run_view(dir, scene + " --script " + bad_script);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("line 2: unknown command 'fly'"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  r = run_view(dir, scene + " --script " + (dir / "missing.txt").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("missing.txt"), std::string::npos) << r.output;
  r = run_view(dir, scene + " --beside " + (dir / "nowhere.toml").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("cannot read the scene"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nowhere.toml"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  r = run_view(dir, scene + " --set particles.colour=red");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("colour"), std::string::npos) << r.output;
  // No scene given and no teaching scene where the assets are: the usual one-line error.
  r = run_view(dir, "", "FLUIDBED_ASSETS=" + dir.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("teaching.toml"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

}  // namespace
}  // namespace fluidbed::testing
