// The presenter mode and two beds side by side (issue 38: what a teacher asked for), driven as a
// teacher would: a pointer and keys through xdotool on a virtual display (ctest's
// ViewWindowUnderXvfb).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "../view/view_scene.hpp"
#include "view_support.hpp"

namespace fluidbed::testing {
namespace {

// The teacher's request: a presenter mode. `--present` opens it: the bed on the left, on the
// right the controls, the words and the live Fig. 6 in larger text, words in the bed; `p`
// switches to the full panel and back.
TEST(ViewWindow, PresenterModeOpensLargeAndThePKeySwitchesIt) {
  REQUIRE_XDOTOOL();
  const auto dir = fresh_dir("present");
  const std::string scene = written_file(dir / "small.toml", kViewTestScene);
  BackgroundView v(dir, scene + " --present --frame-size 1280x720 --out " + (dir / "out").string());
  const auto gas = v.wait_for_widget("present_gas");
  ASSERT_FALSE(gas.empty()) << v.log();
  const auto present = v.widgets();
  ASSERT_TRUE(present.count("bed0"));
  ASSERT_TRUE(present.count("present_curve"));
  ASSERT_TRUE(present.count("bed_labels"));  // the words in the bed are drawn (maybe none yet)
  EXPECT_FALSE(present.count("time"));       // the full panel's top block is not
  EXPECT_LE(number(present.at("bed0"), 2), number(gas, 0) + 1.0);  // the bed left of the words
  EXPECT_GE(number(present.at("present_curve"), 0), number(present.at("bed0"), 2));
  const auto& run = present.at("present_run_button");
  const double tall = number(run, 3) - number(run, 1);
  settle_window();
  ASSERT_TRUE(xdotool("mousemove 100 300"));  // over the bed: the keys go to the window
  ASSERT_TRUE(xdotool("key p"));
  const auto panel = v.wait_for_widget("time", 30);
  ASSERT_FALSE(panel.empty()) << v.log();
  const auto full = v.widgets();
  EXPECT_FALSE(full.count("present_gas"));
  EXPECT_FALSE(full.count("bed_labels"));
  // Text of 24 px against the panel's 18 at 720 px high: buttons (text and 2 x 3 px of frame)
  // a quarter taller.
  const auto& run_panel = full.at("run_button");
  EXPECT_GE(tall, 1.2 * (number(run_panel, 3) - number(run_panel, 1)));
  EXPECT_GT(number(full.at("bed0"), 0), number(full.at("run_button"), 2));  // bed right of panel
  ASSERT_TRUE(xdotool("key p"));
  EXPECT_FALSE(v.wait_for_widget("present_gas", 30).empty()) << v.log();
  EXPECT_TRUE(v.running());
}

}  // namespace
}  // namespace fluidbed::testing

namespace fluidbed::testing {
namespace {

// The teacher's request: two beds side by side. `--beside` runs a second scene on its own engine;
// the gas and a script's `at T` act on both. The panel's button opens the ideal twin beside the
// bed and closes it again.
TEST(ViewWindow, TwoBedsBesideShareTheControlsAndTheIdealTwinOpensAndCloses) {
  REQUIRE_XDOTOOL();
  const auto dir = fresh_dir("beside");
  const std::string a = written_file(dir / "a.toml", kViewTestScene);
  const std::string b = written_file(dir / "b.toml", kViewTestScene);
  const std::string script = written_file(dir / "s.txt", "velocity 1.5\nat 0.02 pause\nquit\n");
  const ViewRun r = run_view(dir, a + " --beside " + b + " --script " + script +
                                      " --frame-size 1024x600 --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const Final first = final_state(r.output);
  EXPECT_NEAR(first.t, 0.02, 1e-3) << r.output;
  EXPECT_NEAR(first.u, 1.5, 1e-9);
  const auto at = r.output.find("beside: stopped at t = ");
  ASSERT_NE(at, std::string::npos) << r.output;
  Final second;
  std::sscanf(r.output.c_str() + at, "beside: stopped at t = %lf s, step %lld, U = %lf", &second.t,
              &second.steps, &second.u);
  EXPECT_NEAR(second.t, 0.02, 1e-3);
  EXPECT_NEAR(second.u, 1.5, 1e-9);
  EXPECT_EQ(second.steps, first.steps);  // the same scene and step: the same count

  // The ideal twin from the panel.
  const auto dir2 = fresh_dir("twin");
  BackgroundView v(dir2, a + " --frame-size 1024x600 --out " + (dir2 / "out").string());
  const auto button = v.wait_for_widget("twin_button");
  ASSERT_FALSE(button.empty()) << v.log();
  settle_window();
  ASSERT_TRUE(click_middle_of(button));
  const auto drawn = v.wait_until(
      "beside_bed", [](const auto& w) { return w.at(4) == "drawn"; }, 60);
  ASSERT_FALSE(drawn.empty()) << v.log();
  const auto bed = v.widgets().at("bed0");
  EXPECT_LE(number(bed, 2), number(drawn, 0) + 1.0);  // the twin right of the bed
  // It runs: its time moves on.
  const double t0 = number(v.wait_for_widget("beside"), 4);
  EXPECT_FALSE(v.wait_until(
                    "beside", [&](const auto& w) { return number(w, 4) > t0; }, 60)
                   .empty());
  ASSERT_TRUE(click_middle_of(v.widgets().at("twin_button")));
  const auto closed = v.wait_until(
      "twin_button", [](const auto& w) { return w.at(4) == "closed"; }, 30);
  EXPECT_FALSE(closed.empty()) << v.log();
  EXPECT_FALSE(v.widgets().count("beside_bed"));
  EXPECT_TRUE(v.running());
}

}  // namespace
}  // namespace fluidbed::testing
