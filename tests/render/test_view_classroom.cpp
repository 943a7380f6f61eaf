// The viewer as a classroom (issue 16): its faults, each driven as a teacher would (a pointer and
// keys through xdotool on a virtual display, ctest's ViewWindowUnderXvfb), the live Fig. 6 from a
// script, captions in the pixels, lessons in the window and headless, and the command line's
// errors for lessons.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../view/view_scene.hpp"
#include "render_support.hpp"
#include "scene/scene_loader.hpp"
#include "sim/simulation.hpp"
#include "view_support.hpp"

namespace fluidbed::testing {
namespace {

namespace fs = std::filesystem;

#define REQUIRE_WINDOW()                                                           \
  do {                                                                             \
    if (!std::getenv("DISPLAY")) {                                                 \
      if (std::getenv("FLUIDBED_REQUIRE_DISPLAY")) FAIL() << "DISPLAY is not set"; \
      GTEST_SKIP() << "no display (ctest runs this test under xvfb-run)";          \
    }                                                                              \
  } while (0)

#define REQUIRE_XDOTOOL()                                                                \
  do {                                                                                   \
    REQUIRE_WINDOW();                                                                    \
    if (!have_xdotool()) {                                                               \
      if (std::getenv("FLUIDBED_REQUIRE_DISPLAY")) FAIL() << "xdotool is not installed"; \
      GTEST_SKIP() << "no xdotool (scripts/install-deps.sh installs it)";                \
    }                                                                                    \
  } while (0)

double number(const std::vector<std::string>& w, std::size_t k) {
  return std::stod(w.at(k));
}

// "viewer: stopped at t = T s, step N, U = U m/s": the engine where the window closed.
struct Final {
  double t = -1.0, u = -1.0;
  long long steps = -1;
};
Final final_state(const std::string& log) {
  Final f;
  const auto at = log.find("viewer: stopped at t = ");
  if (at != std::string::npos)
    std::sscanf(log.c_str() + at, "viewer: stopped at t = %lf s, step %lld, U = %lf", &f.t,
                &f.steps, &f.u);
  return f;
}

const auto red = [](int r, int g, int b) { return r > 190 && g < 70 && b < 70; };
// The caption's white text (the page around the bed is 237 grey).
const auto white = [](int r, int g, int b) { return r > 245 && g > 245 && b > 245; };

// The window mapped and drawing before the pointer acts on it (its first frames come before the
// display has given it the pointer).
void settle_window() {
  std::this_thread::sleep_for(std::chrono::seconds(1));
}

// The fault: a held button on the slider ran U away (the range followed the value). Held for a
// second at 60 % of the slider, U must be what the pointer points at.
TEST(ViewWindow, HeldSliderKeepsTheVelocityUnderThePointer) {
  REQUIRE_XDOTOOL();
  const auto dir = fresh_dir("slider");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string script = written_file(dir / "s.txt", "wait 5\nquit\n");
  BackgroundView v(dir, scene + " --script " + script + " --frame-size 1024x600 --out " +
                            (dir / "out").string());
  ASSERT_FALSE(v.wait_for_widget("velocity_slider").empty()) << v.log();
  settle_window();
  const auto s = v.widgets()["velocity_slider"];
  ASSERT_EQ(s.size(), 7u) << v.log();
  const double x0 = number(s, 0), y0 = number(s, 1), x1 = number(s, 2), y1 = number(s, 3);
  const double top = number(s, 5), grab = number(s, 6);
  // ImGui's slider: the grab's centre runs over the frame less 2 px of padding and the grab.
  const double usable = x1 - x0 - 4.0 - grab;
  const int x = static_cast<int>(std::lround(x0 + 2.0 + 0.5 * grab + 0.6 * usable));
  const int y = static_cast<int>(std::lround(0.5 * (y0 + y1)));
  const double target = top * (x - x0 - 2.0 - 0.5 * grab) / usable;
  ASSERT_TRUE(xdotool("mousemove " + std::to_string(x) + " " + std::to_string(y)));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a frame sees it hover
  ASSERT_TRUE(xdotool("mousedown 1"));
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_TRUE(xdotool("mouseup 1"));
  ASSERT_EQ(v.wait(), 0) << v.log();
  const Final f = final_state(v.log());
  // Within the velocity of one pixel of the slider.
  EXPECT_NEAR(f.u, target, top / usable) << v.log();
  // The range: 2.5 U_mf (the scene's measured U_mf).
  EXPECT_GT(top, 2.0);
}

// The fault: `s` tapped for less than a frame did nothing. Two 10 ms taps: two steps.
TEST(ViewWindow, KeyTapsShorterThanAFrameAct) {
  REQUIRE_XDOTOOL();
  const auto dir = fresh_dir("keys");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string script = written_file(dir / "s.txt", "pause\nwait 4\nquit\n");
  BackgroundView v(dir, scene + " --script " + script + " --frame-size 1024x600 --out " +
                            (dir / "out").string() + " --max-fps 10");
  const auto bed = v.wait_for_widget("bed0");
  ASSERT_FALSE(bed.empty()) << v.log();
  settle_window();
  const int x = static_cast<int>(0.5 * (number(bed, 0) + number(bed, 2)));
  ASSERT_TRUE(xdotool("mousemove " + std::to_string(x) + " 300"));  // the keys go where it points
  for (int k = 0; k < 2; ++k) {
    ASSERT_TRUE(xdotool("keydown s"));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(xdotool("keyup s"));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  ASSERT_EQ(v.wait(), 0) << v.log();
  EXPECT_EQ(final_state(v.log()).steps, 2) << v.log();
}

// The faults: the tracking ring only on the small whole-bed view; `zoom` magnified the labels off
// the screen. The ring must show in the close-up; zoom magnifies the close-up about the tracked
// particle and leaves the labels as they were.
TEST(ViewWindow, TrackingRingShowsInTheCloseUpAndZoomLeavesTheLabels) {
  REQUIRE_WINDOW();
  const auto dir = fresh_dir("track");
  const std::string scene = written_file(dir / "tall.toml", kViewTallScene);
  // A particle in the middle of the close-up (its lower 0.072 m), far enough from the walls and
  // the floor for a view zoomed 3 times to centre on it.
  Simulation sim(parse_scene(kViewTallScene, "tall"));
  const Particles& p = sim.dem().particles();
  std::size_t id = p.size();
  for (std::size_t i = 0; i < p.size() && id == p.size(); ++i)
    if (p.y[i] > 0.025 && p.y[i] < 0.045 && p.x[i] > 0.01 && p.x[i] < 0.02) id = i;
  ASSERT_LT(id, p.size());
  const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string();
  const std::string script =
      written_file(dir / "s.txt", "track " + std::to_string(id) + "\nat 0.005 screenshot " + a +
                                    "\nzoom 3\nscreenshot " + b + "\nquit\n");
  BackgroundView v(dir, scene + " --script " + script + " --frame-size 1024x600 --out " +
                            (dir / "out").string());
  ASSERT_EQ(v.wait(), 0) << v.log();
  const auto w = v.widgets();
  ASSERT_TRUE(w.count("bed1")) << "no close-up at 1024 x 600";
  const auto& z = w.at("bed1");
  EXPECT_EQ(z.at(4), "zoomed");
  const int zx0 = static_cast<int>(number(z, 0)), zy0 = static_cast<int>(number(z, 1));
  const int zx1 = static_cast<int>(number(z, 2)), zy1 = static_cast<int>(number(z, 3));
  const Png pa = read_png(a), pb = read_png(b);
  ASSERT_EQ(pa.w, 1024);
  ASSERT_EQ(pb.w, 1024);
  // The red ring in the close-up (and in the whole bed).
  EXPECT_GT(count_pixels(pa, zx0, zx1, zy0, zy1, red), 20);
  const auto& whole = w.at("bed0");
  EXPECT_GT(
      count_pixels(pa, static_cast<int>(number(whole, 0)), static_cast<int>(number(whole, 2)),
                   static_cast<int>(number(whole, 1)), static_cast<int>(number(whole, 3)), red),
      5);
  // Zoomed 3 times about the particle: its ring (three times wider) about the panel's middle.
  const int cx = (zx0 + zx1) / 2, cy = (zy0 + zy1) / 2, r = (zx1 - zx0) / 4;
  EXPECT_GT(count_pixels(pb, cx - r, cx + r, cy - r, cy + r, red), 60);
  // The labels right of the close-up: the same pixels zoomed or not.
  int differ = 0;
  for (int y = 0; y < 600; ++y)
    for (int x = zx1 + 30; x < 1024; ++x)
      differ += std::equal(pa.at(x, y), pa.at(x, y) + 3, pb.at(x, y)) ? 0 : 1;
  EXPECT_EQ(differ, 0);
}

// The fault: a failure's message was cut at the panel's edge and told the teacher to reduce the
// time step; Reset after a failure left the bed paused. Typed with Ctrl+click, 500 m/s fails on
// the gas CFL number: the message wraps over lines and says what to do; `r` runs the bed again.
TEST(ViewWindow, FailureMessageWrapsAndResetActsAsDuringARun) {
  REQUIRE_XDOTOOL();
  const auto dir = fresh_dir("failure");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  BackgroundView v(dir, scene + " --frame-size 1024x600 --out " + (dir / "out").string());
  ASSERT_FALSE(v.wait_for_widget("velocity_slider").empty()) << v.log();
  settle_window();
  const auto s = v.widgets()["velocity_slider"];
  const auto at = [&](const std::vector<std::string>& w) {
    return std::to_string(static_cast<int>(0.5 * (number(w, 0) + number(w, 2)))) + " " +
           std::to_string(static_cast<int>(0.5 * (number(w, 1) + number(w, 3))));
  };
  ASSERT_TRUE(xdotool("mousemove " + at(s)));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(xdotool("keydown ctrl"));
  ASSERT_TRUE(xdotool("click 1"));
  ASSERT_TRUE(xdotool("keyup ctrl"));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(xdotool("key ctrl+a"));
  ASSERT_TRUE(xdotool("type 500"));
  ASSERT_TRUE(xdotool("key Return"));
  // The failure, then a screenshot from the panel's button.
  std::vector<std::string> error;
  for (int k = 0; k < 600 && (error.size() < 5 || error[4] != "shown"); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    error = v.widgets()["error"];
  }
  ASSERT_EQ(error.size(), 5u) << v.log();
  ASSERT_EQ(error[4], "shown");
  ASSERT_TRUE(xdotool("mousemove " + at(v.widgets()["screenshot_button"])));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(xdotool("click 1"));
  const fs::path shot = dir / "out" / "screenshot_001.png";
  for (int k = 0; k < 200 && !fs::exists(shot); ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const Png p = read_png(shot.string());
  ASSERT_EQ(p.w, 1024) << v.log();
  // The message's red text: on more than two lines, and none of it beyond the panel's edge.
  const int font = static_cast<int>(number(v.widgets()["window"], 4));
  int first = -1, last = -1;
  const auto message_red = [](int r, int g, int b) {
    return r > 200 && g > 80 && g < 150 && b < 110;
  };
  for (int y = 0; y < 600; ++y)
    if (count_pixels(p, 0, 360, y, y + 1, message_red) > 0) {
      if (first < 0) first = y;
      last = y;
    }
  EXPECT_GT(last - first, 2 * font) << "the message stays on one line";
  EXPECT_EQ(count_pixels(p, 376, 1024, 0, 600, message_red), 0);
  // Reset (the key): running again from the packed bed, as Reset during a run.
  ASSERT_TRUE(xdotool("mousemove 700 300"));
  ASSERT_TRUE(xdotool("key r"));
  for (int k = 0; k < 600; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const auto w = v.widgets();
    if (w.count("state") && w.at("state").size() >= 5 && w.at("state")[4] == "running" &&
        w.count("error") && w.at("error")[4] == "none")
      break;
  }
  const auto w = v.widgets();
  EXPECT_EQ(w.at("error").at(4), "none");
  EXPECT_EQ(w.at("state").at(4), "running");
}

}  // namespace
}  // namespace fluidbed::testing

namespace fluidbed::testing {
namespace {

// The fault: at a high velocity the overlap reached 6.2 % with no warning. Soft contacts (30 N/m:
// the bed's weight presses the bottom layers about 7 % into each other) must bring the warning.
TEST(ViewWindow, DeepOverlapsAreWarnedOf) {
  REQUIRE_WINDOW();
  const auto dir = fresh_dir("overlap");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string script =
      written_file(dir / "s.txt", "at 0.3 screenshot " + (dir / "a.png").string() + "\nquit\n");
  BackgroundView v(dir, scene + " --set contact.stiffness=30 --script " + script +
                            " --frame-size 1024x600 --out " + (dir / "out").string());
  ASSERT_EQ(v.wait(), 0) << v.log();
  const auto w = v.widgets();
  ASSERT_TRUE(w.count("overlap_warning")) << v.log();
  EXPECT_GT(number(w.at("overlap_warning"), 4), 0.05);
  // At 1024 x 600 the panel's buttons are all on the screen, and the bed is wide enough to see.
  for (const char* name : {"run_button", "reset_button", "screenshot_button", "record_button"}) {
    ASSERT_TRUE(w.count(name)) << name;
    EXPECT_LE(number(w.at(name), 3), 600.0) << name;
  }
  EXPECT_GE(number(w.at("bed0"), 2) - number(w.at("bed0"), 0), 60.0);
}

// Reads a CSV's rows (header left out).
std::vector<std::string> csv_rows(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) rows.push_back(line);
  return rows;
}

// A scripted run that holds three velocities gets three points on the increasing branch; a
// lower velocity starts the decreasing one; Reset clears the curve; the saved CSV has the rows.
TEST(ViewWindow, ScriptedHoldsBuildTheLiveCurve) {
  REQUIRE_WINDOW();
  const auto dir = fresh_dir("curve");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string c1 = (dir / "c1.csv").string(), c2 = (dir / "c2.csv").string(),
                    c3 = (dir / "c3.csv").string(), png = (dir / "c2.png").string();
  const std::string script = written_file(dir / "s.txt",
                                        "settle 0.01\naverage 0.02\n"
                                        "at 0.04 velocity 2.5\n"
                                        "at 0.08 velocity 3.0\n"
                                        "at 0.12 curve " +
                                            c1 +
                                            "\n"
                                            "velocity 2.2\n"
                                            "at 0.16 curve " +
                                            c2 +
                                            "\n"
                                            "curve " +
                                            png +
                                            "\n"
                                            "reset\n"
                                            "curve " +
                                            c3 +
                                            "\n"
                                            "quit\n");
  const ViewRun r = run_view(dir, scene + " --script " + script + " --frame-size 1024x600 --out " +
                                      (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto up = csv_rows(c1);
  ASSERT_EQ(up.size(), 3u) << r.output;
  EXPECT_EQ(up[0].rfind("1,increasing,2,", 0), 0u) << up[0];
  EXPECT_EQ(up[1].rfind("1,increasing,2.5,", 0), 0u) << up[1];
  EXPECT_EQ(up[2].rfind("1,increasing,3,", 0), 0u) << up[2];
  const auto both = csv_rows(c2);
  ASSERT_EQ(both.size(), 4u);
  EXPECT_EQ(both[3].rfind("2,decreasing,2.2,", 0), 0u) << both[3];
  EXPECT_TRUE(csv_rows(c3).empty());
  EXPECT_EQ(read_png(png).w, 1200);
}

// Captions are drawn in the band over the bed: in a screenshot the band's pixels differ from the
// caption-free frame, and its text is white on the band's dark blue.
TEST(ViewWindow, CaptionShowsInTheScreenshot) {
  REQUIRE_WINDOW();
  const auto dir = fresh_dir("caption");
  const std::string scene = written_file(dir / "tall.toml", kViewTallScene);
  const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string();
  const std::string script =
      written_file(dir / "s.txt", "screenshot " + a +
                                    "\ncaption \"The bed is packed: the gas seeps through.\"\n"
                                    "screenshot " +
                                    b + "\nquit\n");
  const ViewRun r = run_view(dir, scene + " --script " + script + " --frame-size 1024x600 --out " +
                                      (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Png pa = read_png(a), pb = read_png(b);
  ASSERT_EQ(pa.w, 1024);
  // The band: the top 3.1 x 1.35 x (600 / 40) px of the bed area.
  const int band = 60, x0 = 400;
  int differ = 0;
  for (int y = 0; y < band; ++y)
    for (int x = x0; x < 1024; ++x)
      differ += std::equal(pa.at(x, y), pa.at(x, y) + 3, pb.at(x, y)) ? 0 : 1;
  EXPECT_GT(differ, 5000);
  EXPECT_GT(count_pixels(pb, x0, 1024, 0, band, white), 150);
  EXPECT_EQ(count_pixels(pa, x0, 1024, 0, band, white), 0);
}

// `view --help` says the size the window opens at, and it opens at it.
TEST(ViewWindow, OpensAtTheSizeItsHelpSays) {
  REQUIRE_WINDOW();
  const auto dir = fresh_dir("size");
  const ViewRun help = run_view(dir, "--help");
  ASSERT_EQ(help.status, 0);
  const auto at = help.output.find("window size WxH in pixels (");
  ASSERT_NE(at, std::string::npos) << help.output;
  int w = 0, h = 0;
  ASSERT_EQ(std::sscanf(help.output.c_str() + at, "window size WxH in pixels (%dx%d", &w, &h), 2);
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  const std::string shot = (dir / "a.png").string();
  const std::string script = written_file(dir / "s.txt", "screenshot " + shot + "\nquit\n");
  const ViewRun r =
      run_view(dir, scene + " --script " + script + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Png p = read_png(shot);
  EXPECT_EQ(p.w, w);
  EXPECT_EQ(p.h, h);
}

// An assets folder of the shipped scenes and fonts and one short lesson of the test's own: the
// lesson mechanism (a scene named by the lesson, captions, a preset) without minutes of bed.
fs::path assets_with_lesson(const fs::path& dir, const std::string& lesson_text) {
  const fs::path assets = dir / "assets";
  fs::create_directories(assets / "lessons");
  fs::create_directory_symlink(fs::path(FLUIDBED_ASSET_DIR) / "fonts", assets / "fonts");
  fs::create_directories(assets / "scenes");
  written_file(assets / "scenes" / "tall.toml", kViewTallScene);
  written_file(assets / "lessons" / "short.txt", lesson_text);
  return assets;
}

const char* kShortLesson = R"(# A short lesson for the tests
scene tall.toml
caption "Packed: the gas seeps through the bed."
at 0.02 preset bubbling
at 0.02 caption "Past U_mf the extra gas rises as bubbles."
at 0.04 quit
)";

TEST(ViewWindow, LessonRunsToItsEndWithItsCaptions) {
  REQUIRE_WINDOW();
  const auto dir = fresh_dir("lesson");
  const fs::path assets = assets_with_lesson(
      dir, std::string(kShortLesson)
               .replace(std::string(kShortLesson).find("at 0.04 quit"), 12,
                        "at 0.03 screenshot " + (dir / "shot.png").string() + "\nat 0.04 quit"));
  const ViewRun r =
      run_view(dir, "--lesson short --frame-size 1024x600 --out " + (dir / "out").string(),
               "FLUIDBED_ASSETS=" + assets.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NEAR(final_state(r.output).t, 0.04, 1e-5) << r.output;  // the step nearest 0.04 s
  const Png p = read_png((dir / "shot.png").string());
  ASSERT_EQ(p.w, 1024);
  EXPECT_GT(count_pixels(p, 400, 1024, 0, 60, white), 150);
}

// Without a display a lesson becomes a video with its captions (DIR/video.mp4, and the frames).
TEST(ViewCommand, LessonWithoutADisplayMakesAVideoWithCaptions) {
  const auto dir = fresh_dir("lesson_headless");
  const fs::path assets = assets_with_lesson(dir, kShortLesson);
  const fs::path out = dir / "out";
  const ViewRun r = run_view(
      dir, "--lesson short --frame-size 640x360 --frame-interval 0.01 --out " + out.string(),
      "env -u DISPLAY -u WAYLAND_DISPLAY FLUIDBED_ASSETS=" + assets.string());
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_TRUE(fs::exists(out / "video.mp4")) << r.output;
  EXPECT_GT(fs::file_size(out / "video.mp4"), 1000u);
  // Frames every 0.01 s: the first caption at 0 s, the second from 0.02 s.
  const Png first = read_png((out / "frames" / "frame_000000.png").string());
  const Png later = read_png((out / "frames" / "frame_000004.png").string());
  ASSERT_EQ(first.w, 640) << r.output;
  ASSERT_EQ(later.w, 640);
  const int band = static_cast<int>(std::lround(3.1 * std::round(1.35 * std::round(360 / 40.0))));
  // The band is dark blue under a caption: its light pixels are the caption's letters.
  const auto light = [](int r_, int g, int b_) { return r_ > 200 && g > 200 && b_ > 200; };
  EXPECT_GT(count_pixels(first, 0, 380, 0, band, light), 100);
  int differ = 0;
  for (int y = 0; y < band; ++y)
    for (int x = 0; x < 380; ++x)
      differ += std::equal(first.at(x, y), first.at(x, y) + 3, later.at(x, y)) ? 0 : 1;
  EXPECT_GT(differ, 200) << "the second caption";
  // ffprobe reads the video: 5 frames (0 to 0.04 s).
  const std::string probe =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames -of csv=p=0 " +
      (out / "video.mp4").string() + " > " + (dir / "probe.txt").string();
  ASSERT_EQ(std::system(probe.c_str()), 0);
  std::ifstream in(dir / "probe.txt");
  int n = 0;
  in >> n;
  EXPECT_EQ(n, 5);
}

// Lessons: a name that is not one, an unreadable one, an unknown command in one: one line, exit
// status 2; --list-lessons lists the shipped ones.
TEST(ViewCommand, LessonErrorsAreOneLineAndTheShippedOnesAreListed) {
  const auto dir = fresh_dir("lesson_errors");
  ViewRun r = run_view(dir, "--lesson nosuch", "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("no lesson 'nosuch' (known: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("hysteresis"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  // Unreadable: a folder where the lesson's file should be.
  const fs::path assets = assets_with_lesson(dir, "# broken\nvelocity 1\nfly away\n");
  fs::create_directories(assets / "lessons" / "folder.txt");
  const std::string env = "env -u DISPLAY -u WAYLAND_DISPLAY FLUIDBED_ASSETS=" + assets.string();
  r = run_view(dir, "--lesson folder", env);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("folder.txt"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  r = run_view(dir, "--lesson short", env);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("short.txt line 3: unknown command 'fly'"), std::string::npos)
      << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  r = run_view(dir, "--lesson short --script x.txt", env);
  EXPECT_EQ(r.status, 2) << r.output;
  r = run_view(dir, "--list-lessons");
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char* name : {"hysteresis", "bubbles-and-slugs", "ideal-vs-real", "soft-vs-stiff"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name << "\n" << r.output;
}

// Every shipped lesson names a scene that loads, uses only commands its scene takes (a stiffness
// its step can take, presets on a bed with gas) and ends with quit: checked by running it to
// t = 0 without a display.
TEST(ViewCommand, ShippedLessonsAreAcceptedByTheirScenes) {
  const auto dir = fresh_dir("lessons_check");
  for (const char* name : {"hysteresis", "bubbles-and-slugs", "ideal-vs-real", "soft-vs-stiff"}) {
    const ViewRun r = run_view(dir,
                               std::string("--lesson ") + name +
                                   " --until 0 --frame-size 320x180 --out " + (dir / name).string(),
                               "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_EQ(r.status, 0) << name << "\n" << r.output;
    std::ifstream in(fs::path(FLUIDBED_ASSET_DIR) / "lessons" / (std::string(name) + ".txt"));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find(" quit"), std::string::npos) << name;
    EXPECT_NE(text.find("caption"), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace fluidbed::testing
