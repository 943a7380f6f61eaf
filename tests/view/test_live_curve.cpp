// The viewer's live Fig. 6 (view/live_curve.hpp), the panel's sizes and plot ranges
// (view/panel_layout.hpp), the presets and the new script commands. No threads, no GL.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "view/live_curve.hpp"
#include "view/panel_layout.hpp"
#include "view/presets.hpp"
#include "view/regime_watch.hpp"
#include "view/script.hpp"
#include "view/script_runner.hpp"
#include "view/status_words.hpp"
#include "view_scene.hpp"

namespace fluidbed {
namespace {

using app::CurveState;
using app::HoldPhase;
using app::LiveCurve;

constexpr double kStep = 1e-3;  // s between dp samples, as the engine's output interval

// Samples every millisecond from t to t_end, dp(t).
template <class F>
double feed(LiveCurve& c, double t, double t_end, F dp) {
  for (; t < t_end - 1e-12;) {
    t += kStep;
    c.sample(t, dp(t));
  }
  return t;
}

int own_points(const app::CurveBranch& b) {
  int n = 0;
  for (const auto& p : b.points) n += p.shared ? 0 : 1;
  return n;
}

TEST(LiveCurve, OnePointPerHeldVelocityAfterSettlingAndAveraging) {
  LiveCurve c(0.2, 0.3, 3550.0, 0.0, 1.0);
  EXPECT_EQ(c.state().phase, HoldPhase::settling);
  // 1 m/s: settling the first 0.2 s (its dp is not averaged), then 0.3 s of 1000 Pa.
  double t = feed(c, 0.0, 0.2, [](double) { return 9000.0; });
  EXPECT_EQ(c.state().phase, HoldPhase::averaging);
  t = feed(c, t, 0.5, [](double) { return 1000.0; });
  ASSERT_EQ(c.state().branches.size(), 1u);
  ASSERT_EQ(c.state().branches[0].points.size(), 1u);
  const app::CurvePoint& p = c.state().branches[0].points[0];
  EXPECT_EQ(p.u, 1.0);
  EXPECT_NEAR(p.dp_mean, 1000.0, 1e-9);  // the spike of the settling time is left out
  EXPECT_EQ(p.samples, 300);
  EXPECT_NEAR(p.t_from, 0.2, 1e-12);
  EXPECT_NEAR(p.t_to, 0.5, 1e-12);
  EXPECT_EQ(c.state().phase, HoldPhase::done);
  // Held longer: still one point.
  t = feed(c, t, 1.5, [](double) { return 1000.0; });
  EXPECT_EQ(c.state().branches[0].points.size(), 1u);
  // Two more velocities upwards: the increasing branch.
  c.velocity(t, 2.0);
  t = feed(c, t, t + 0.5, [](double) { return 2000.0; });
  c.velocity(t, 3.0);
  t = feed(c, t, t + 0.5, [](double) { return 3000.0; });
  ASSERT_EQ(c.state().branches.size(), 1u);
  EXPECT_TRUE(c.state().branches[0].increasing);
  ASSERT_EQ(c.state().branches[0].points.size(), 3u);
  EXPECT_NEAR(c.state().branches[0].points[2].dp_mean, 3000.0, 1e-9);
  // Down: a decreasing branch that starts at the turning point (3 m/s), shared.
  c.velocity(t, 2.5);
  ASSERT_EQ(c.state().branches.size(), 2u);
  EXPECT_FALSE(c.state().branches[1].increasing);
  ASSERT_EQ(c.state().branches[1].points.size(), 1u);
  EXPECT_TRUE(c.state().branches[1].points[0].shared);
  EXPECT_EQ(c.state().branches[1].points[0].u, 3.0);
  t = feed(c, t, t + 0.5, [](double) { return 2800.0; });
  EXPECT_EQ(own_points(c.state().branches[1]), 1);
  // The CSV: each point once, on the branch it was taken on.
  std::ostringstream csv;
  app::write_curve_csv(csv, c.state());
  EXPECT_EQ(csv.str(),
            "branch,direction,u_m_s,dp_mean_pa,dp_std_pa,samples,t_from_s,t_to_s,settle_s\n"
            "1,increasing,1,1000,0,300,0.2,0.5,0.2\n"
            "1,increasing,2,2000,0,300,1.7,2,0.2\n"
            "1,increasing,3,3000,0,300,2.2,2.5,0.2\n"
            "2,decreasing,2.5,2800,0,300,2.7,3,0.2\n");
  // Reset: nothing, the increasing branch again.
  const auto version = c.state().version;
  c.clear(0.0, 2.8);
  EXPECT_GT(c.state().version, version);
  ASSERT_EQ(c.state().branches.size(), 1u);
  EXPECT_TRUE(c.state().branches[0].points.empty());
  EXPECT_TRUE(c.state().branches[0].increasing);
  EXPECT_EQ(c.state().held_u, 2.8);
}

TEST(LiveCurve, ATurnAndBackBeforeAnyPointKeepsTheBranch) {
  LiveCurve c(0.0, 0.1, 100.0, 0.0, 1.0);
  double t = feed(c, 0.0, 0.1, [](double) { return 10.0; });
  c.velocity(t, 2.0);
  t = feed(c, t, t + 0.1, [](double) { return 20.0; });
  c.velocity(t, 1.5);  // down: a new branch from (2, 20)
  ASSERT_EQ(c.state().branches.size(), 2u);
  c.velocity(t + 0.05, 2.5);  // up again before 1.5 m/s gave a point: the first branch goes on
  ASSERT_EQ(c.state().branches.size(), 1u);
  feed(c, t + 0.05, t + 0.2, [](double) { return 25.0; });
  EXPECT_EQ(c.state().branches[0].points.size(), 3u);
  // Before any point the bed is the packed one: a first change down stays on the increasing
  // branch.
  LiveCurve d(0.0, 0.1, 100.0, 0.0, 3.0);
  d.velocity(0.0, 2.0);
  feed(d, 0.0, 0.1, [](double) { return 5.0; });
  ASSERT_EQ(d.state().branches.size(), 1u);
  EXPECT_TRUE(d.state().branches[0].increasing);
  ASSERT_EQ(d.state().branches[0].points.size(), 1u);
  // A slider dragged from 2 past 3 and back to 3 m/s: one change up.
  d.velocity(0.1, 3.2);
  d.velocity(0.11, 3.0);
  EXPECT_EQ(d.state().branches.size(), 1u);
}

// Samples on a grid that misses the window's end: a change within a sample and a half of it
// still completes the point.
TEST(LiveCurve, AChangeAtTheWindowsEndCompletesThePoint) {
  LiveCurve c(0.5, 1.0, 100.0, 0.0, 1.0);
  const double spacing = 1e-3;
  double t = 0.2e-3 - spacing;  // the grid's last sample before 1.5 s comes 0.8 ms before it
  while (t + spacing < 1.5) {
    t += spacing;
    c.sample(t, 42.0);
  }
  EXPECT_TRUE(c.state().branches[0].points.empty());  // the last sample before 1.5 s
  c.velocity(1.5, 2.0);
  ASSERT_EQ(c.state().branches[0].points.size(), 1u);
  EXPECT_EQ(c.state().branches[0].points[0].u, 1.0);
  EXPECT_NEAR(c.state().branches[0].points[0].dp_mean, 42.0, 1e-12);
}

TEST(LiveCurve, FitsUmfOnTheDecreasingBranchAsTheSweepDoes) {
  // A plateau of 3000 Pa above 2 m/s, the defluidization line 1500 U below it.
  const auto dp_of = [](double u) { return u < 2.0 ? 1500.0 * u : 3000.0; };
  LiveCurve c(0.0, 0.05, 3000.0, 0.0, 3.0);
  double t = feed(c, 0.0, 0.05, [&](double) { return dp_of(3.0); });
  for (double u : {2.6, 2.2, 1.8, 1.4, 1.0}) {
    c.velocity(t, u);
    t = feed(c, t, t + 0.05, [&](double) { return dp_of(u); });
    if (u == 2.2) {
      EXPECT_FALSE(c.state().umf.ok);  // 3 points: too few for the fit
    }
  }
  // The first point (3 m/s, the start) on the increasing branch, the decreasing one from it.
  ASSERT_EQ(c.state().branches.size(), 2u);
  EXPECT_EQ(c.state().branches[1].points.size(), 6u);
  ASSERT_TRUE(c.state().umf.ok) << c.state().umf.why;
  EXPECT_NEAR(c.state().umf.umf, 2.0, 1e-6);
  EXPECT_NEAR(c.state().umf.plateau, 3000.0, 1e-6);
  // Going up again: the decreasing branch keeps its fit.
  c.velocity(t, 1.5);
  c.velocity(t + 0.01, 2.0);
  EXPECT_TRUE(c.state().umf.ok);
}

TEST(LiveCurve, NewTimesRestartTheAveragingAndBadOnesAreRefused) {
  LiveCurve c(0.5, 1.0, 100.0, 0.0, 1.0);
  double t = feed(c, 0.0, 0.7, [](double) { return 5.0; });
  c.set_times(t, 0.1, 0.2);  // the hold started at 0: settled already, averaging from now
  EXPECT_EQ(c.state().phase, HoldPhase::averaging);
  t = feed(c, t, t + 0.2, [](double) { return 7.0; });
  ASSERT_EQ(c.state().branches[0].points.size(), 1u);
  EXPECT_NEAR(c.state().branches[0].points[0].dp_mean, 7.0, 1e-12);
  EXPECT_THROW(c.set_times(t, -1.0, 1.0), InputError);
  EXPECT_THROW(c.set_times(t, 0.5, 0.0), InputError);
  EXPECT_THROW(LiveCurve(0.5, std::nan(""), 1.0, 0.0, 1.0), InputError);
}

TEST(PanelLayout, TextAndPanelGrowWithTheWindow) {
  const app::PanelLayout small = app::panel_layout(1024, 600);
  EXPECT_EQ(small.font, 15.0f);
  EXPECT_EQ(small.width, 375.0f);  // leaves 649 px for the bed
  const app::PanelLayout hd = app::panel_layout(1280, 720);
  EXPECT_EQ(hd.font, 18.0f);
  EXPECT_EQ(hd.width, 450.0f);
  EXPECT_EQ(app::panel_layout(1920, 1080).font, 24.0f);
  // A squarer window: the text of a 16:9 window as wide, so that the beds keep their width.
  EXPECT_EQ(app::panel_layout(1400, 900).font, 21.0f);
  // A narrow window keeps at least 55 % for the bed.
  EXPECT_LE(app::panel_layout(640, 480).width, 0.45f * 640.0f);
}

TEST(PanelLayout, PlotRangeIgnoresTheStartUpSpike) {
  // 2 s of bubbling dp (3000 +- 300 Pa) after a 40 ms start-up spike to 13,600 Pa.
  std::vector<float> dp;
  for (int k = 0; k < 2000; ++k) {
    const double t = 1e-3 * k;
    dp.push_back(static_cast<float>(t < 0.04 ? 13600.0 - 2.5e5 * t
                                             : 3000.0 + 300.0 * std::sin(2.0 * M_PI * 2.0 * t)));
  }
  const auto [lo, hi] = app::robust_range(dp);
  EXPECT_GT(lo, 2600.0);
  EXPECT_LT(hi, 3400.0);  // min-max would reach 13,600: the bubbling a flat line
  EXPECT_GT(hi - lo, 600.0);
  const auto [a, b] = app::robust_range({5.0f, 5.0f});
  EXPECT_LT(a, 5.0);
  EXPECT_GT(b, 5.0);
}

TEST(ViewScript, ParsesTheClassroomCommands) {
  const app::ViewScript s = app::parse_view_script(R"(scene teaching.toml
# a lesson
at 0.5 caption "The jet lifts the bed # not a comment"
caption off
velocity 1.2 umf
preset bubbling
stiffness 800
stiffness scene
settle 0.4
average 1.5
curve out/fig6.csv
)",
                                                   "lesson.txt");
  EXPECT_EQ(s.scene, "teaching.toml");
  ASSERT_EQ(s.lines.size(), 9u);
  using K = app::ScriptLine::Kind;
  EXPECT_EQ(s.lines[0].kind, K::caption);
  EXPECT_EQ(s.lines[0].text, "The jet lifts the bed # not a comment");
  EXPECT_EQ(s.lines[0].at, 0.5);
  EXPECT_EQ(s.lines[1].text, "");
  EXPECT_EQ(s.lines[2].kind, K::velocity);
  EXPECT_EQ(s.lines[2].text, "umf");
  EXPECT_EQ(s.lines[2].number, 1.2);
  EXPECT_EQ(s.lines[3].kind, K::preset);
  EXPECT_EQ(s.lines[4].number, 800.0);
  EXPECT_EQ(s.lines[5].number, 0.0);
  EXPECT_EQ(s.lines[6].kind, K::settle);
  EXPECT_EQ(s.lines[7].number, 1.5);
  EXPECT_EQ(s.lines[8].text, "out/fig6.csv");
  EXPECT_TRUE(s.needs_umf());
  const auto message = [](const std::string& text) {
    return testing::script_error(app::parse_view_script, text);
  };
  EXPECT_NE(message("preset boiling").find("unknown preset 'boiling'"), std::string::npos);
  EXPECT_NE(message("caption \"open").find("not closed"), std::string::npos);
  EXPECT_NE(message("velocity 1 fast").find("umf"), std::string::npos);
  EXPECT_NE(message("curve fig.jpg").find("FILE.csv or FILE.png"), std::string::npos);
  EXPECT_NE(message("average 0").find("> 0"), std::string::npos);
  EXPECT_NE(message("run\nscene x.toml").find("before every other command"), std::string::npos);
  EXPECT_NE(message("stiffness -5").find("> 0"), std::string::npos);
}

// Presets and velocities in U_mf become velocities of the target's U_mf; without one they are
// not carried out.
// An `at T` the bed has already passed (a wait ran it on in the window) is carried out at once and
// said in the log, with the line and the time it came at; one on time or at the step nearest T
// says nothing.
TEST(ScriptRunner, AnAtBehindItsTimeIsReported) {
  struct Target : app::ScriptTarget {
    double t = 0.0;
    std::vector<std::string> notes;
    int captions = 0;
    void run_to(double) override {}
    bool busy() override { return false; }
    bool stopped() const override { return false; }
    void unsupported(const app::ScriptLine&) override {}
    double sim_time() const override { return t; }
    double sim_step() const override { return 0.01; }
    void note(const std::string& text) override { notes.push_back(text); }
    bool caption(const std::string&) override { return ++captions > 0; }
  };
  Target on_time;
  on_time.t = 0.104;  // the step nearest 0.1 s is 0.10: within half a step
  app::ScriptRunner(app::parse_view_script("at 0.1 caption a", "s").lines).advance(on_time);
  EXPECT_TRUE(on_time.notes.empty());
  EXPECT_EQ(on_time.captions, 1);
  Target late;
  late.t = 1.36;
  app::ScriptRunner(app::parse_view_script("caption a\nat 1.2 caption b", "s").lines)
      .advance(late);
  EXPECT_EQ(late.captions, 2);  // carried out all the same
  ASSERT_EQ(late.notes.size(), 1u);
  EXPECT_EQ(late.notes[0], "script line 2: `at 1.2` came late, at t = 1.36 s: an earlier line "
                           "(a wait, steps) ran the bed past it");
}

TEST(ScriptRunner, PresetsAreMultiplesOfTheScenesUmf) {
  struct Target : app::ScriptTarget {
    double u = -1.0, measured = 0.0;
    int unsupported_lines = 0;
    void run_to(double) override {}
    bool busy() override { return false; }
    bool stopped() const override { return false; }
    void unsupported(const app::ScriptLine&) override { ++unsupported_lines; }
    double umf() const override { return measured; }
    bool velocity(double v) override {
      u = v;
      return true;
    }
  };
  Target t;
  t.measured = 2.0;
  app::ScriptRunner(app::parse_view_script("preset slugging", "s").lines).advance(t);
  EXPECT_DOUBLE_EQ(t.u, 2.0 * app::find_preset("slugging")->umf_multiple);
  app::ScriptRunner(app::parse_view_script("velocity 0.5 umf", "s").lines).advance(t);
  EXPECT_DOUBLE_EQ(t.u, 1.0);
  Target none;
  app::ScriptRunner(app::parse_view_script("preset fixed\nvelocity 1 umf", "s").lines)
      .advance(none);
  EXPECT_EQ(none.u, -1.0);
  EXPECT_EQ(none.unsupported_lines, 2);
  // The stages in the order of Fig. 6.
  double last = 0.0;
  for (const app::Preset& p : app::kPresets) {
    EXPECT_GT(p.umf_multiple, last) << p.name;
    last = p.umf_multiple;
  }
}

}  // namespace
}  // namespace fluidbed

namespace fluidbed {
namespace {

// A screenshot a script takes at `at T` shows the bed as the script runs it, and the speed it
// measured; the speed in words beside the figure.
TEST(StatusWords, RunningWhileAScriptRunsTheBedAndSlowMotionBesideTheFigure) {
  app::EngineStatus st;
  EXPECT_EQ(app::run_state_words(st, false), "paused");
  EXPECT_EQ(app::run_state_words(st, true), "running");  // stopped at `at T` for a screenshot
  st.run_until = 0.3;
  st.stepping = true;
  EXPECT_EQ(app::run_state_words(st, true), "running to t = 0.300 s (script)");
  st.error = "the simulation failed: ...";
  EXPECT_EQ(app::run_state_words(st, true), "stopped: the simulation failed");
  EXPECT_EQ(app::speed_words(1.0 / 15.0), "slow motion x 15.0 (0.0667 sim s per wall s)");
  EXPECT_EQ(app::speed_words(1.02), "real time (1.02 sim s per wall s)");
  EXPECT_EQ(app::speed_words(2.0), "fast motion x 2.0 (2 sim s per wall s)");
  EXPECT_EQ(app::speed_words(0.0), "speed: not measured yet");
}

}  // namespace
}  // namespace fluidbed

namespace fluidbed {
namespace {

// The bubble under the pointer: the region whose cells hold the point.
TEST(BubbleView, FindsTheRegionUnderAPointAndSaysTheRegime) {
  app::BubbleView v;
  v.grid.nx = 4;
  v.grid.ny = 3;
  v.grid.dx = v.grid.dy = 0.002;
  v.label = {kCellDense,
             0,
             0,
             kCellDense,  // row 0 (the bottom)
             kCellDense,
             0,
             1,
             kCellDense,  //
             kCellFreeboard,
             kCellFreeboard,
             kCellFreeboard,
             kCellFreeboard};
  v.regions.resize(2);
  v.regions[0].id = 7;
  v.regions[1].id = 9;
  ASSERT_NE(v.region_at(0.003, 0.001), nullptr);
  EXPECT_EQ(v.region_at(0.003, 0.001)->id, 7);
  EXPECT_EQ(v.region_at(0.005, 0.003)->id, 9);
  EXPECT_EQ(v.region_at(0.001, 0.001), nullptr);  // dense
  EXPECT_EQ(v.region_at(0.005, 0.005), nullptr);  // freeboard
  EXPECT_EQ(v.region_at(0.009, 0.001), nullptr);  // outside the grid
  EXPECT_EQ(v.region_at(-0.001, 0.001), nullptr);
  v.shown = Regime::slugging;
  v.window_s = 1.0;
  EXPECT_EQ(app::regime_words(v), "slugging");
  v.shown = Regime::fixed;
  v.window_s = 0.2;
  EXPECT_EQ(app::regime_words(v), "fixed bed?");
}

// The fault: the label changed between bubbling and slugging every few seconds at 2.8 m/s, and
// within a second. On a recorded sequence (a frame every 0.01 s): a flicker between the two never
// reaches the label; a change that lasts is shown one second after it began, not before.
TEST(RegimeLabel, HoldsASecondAndShowsAChangeThatLasts) {
  app::RegimeLabel label;
  double t = 0.0;
  const auto run = [&](double until, auto raw_at) {
    Regime shown = label.shown();
    for (; t < until - 1e-9; t += 0.01) shown = label.update(t, raw_at(t));
    return shown;
  };
  EXPECT_EQ(run(2.0, [](double) { return Regime::bubbling; }), Regime::bubbling);
  // 2 s of flicker: slugging and bubbling in turns of 0.3 s.
  Regime worst = Regime::bubbling;
  for (double end = 2.3; end < 4.0 + 1e-9; end += 0.3) {
    const Regime r = static_cast<int>(std::lround(end / 0.3)) % 2 == 0 ? Regime::slugging
                                                                        : Regime::bubbling;
    if (run(end, [r](double) { return r; }) != Regime::bubbling) worst = Regime::slugging;
  }
  EXPECT_EQ(worst, Regime::bubbling) << "the label followed a flicker";
  // Slugging from t = 4.0 on: still bubbling at 4.9 s, slugging from 5.0 s.
  const double start = t;
  EXPECT_EQ(run(start + 0.9, [](double) { return Regime::slugging; }), Regime::bubbling);
  EXPECT_EQ(run(start + 1.05, [](double) { return Regime::slugging; }), Regime::slugging);
  label.restart();
  EXPECT_EQ(label.update(0.0, Regime::fixed), Regime::fixed);  // a reset shows what it sees
}

// The fault: "rising at -0.41 m/s" under the pointer, and a mean rise of -0.09 m/s in the panel.
// A rise velocity is shown only for a bubble tracked over the frames a track needs, moving up;
// the jet's cavity, a young track and a falling centre get words instead, never a velocity.
TEST(BubbleView, OnlyALastingRisingBubbleShowsARiseVelocity) {
  Bubble b;
  b.has_velocity = true;
  b.vy = 0.35;
  app::RiseShown r = app::rise_shown(b, 5, 3);
  EXPECT_TRUE(r.shown);
  EXPECT_EQ(r.vy, 0.35);
  r = app::rise_shown(b, 2, 3);  // a track too short
  EXPECT_FALSE(r.shown);
  EXPECT_NE(r.words.find("tracked over 2 of the 3 frames"), std::string::npos) << r.words;
  b.vy = -0.41;  // a collapsing void
  r = app::rise_shown(b, 10, 3);
  EXPECT_FALSE(r.shown);
  EXPECT_NE(r.words.find("not rising"), std::string::npos) << r.words;
  EXPECT_EQ(r.words.find("-0.41"), std::string::npos);
  b.vy = 0.8;
  b.touches_jet = true;
  EXPECT_FALSE(app::rise_shown(b, 10, 3).shown);
  b.touches_jet = false;
  b.has_velocity = false;
  EXPECT_FALSE(app::rise_shown(b, 10, 3).shown);
  // The panel's mean: upwards, its figure; downwards, words without a negative figure.
  BubbleStatistics w;
  EXPECT_EQ(app::mean_rise_words(w), "");
  w.velocity_samples = 12;
  w.mean_rise_velocity_m_s = 0.27;
  EXPECT_EQ(app::mean_rise_words(w), "rising at 0.27 m/s");
  w.mean_rise_velocity_m_s = -0.09;
  EXPECT_EQ(app::mean_rise_words(w).find("-0.09"), std::string::npos);
  EXPECT_NE(app::mean_rise_words(w).find("did not rise"), std::string::npos);
}

}  // namespace
}  // namespace fluidbed

namespace fluidbed {
namespace {

// The presenter mode: text from the back of a room, the bed on the left, the class's words.
TEST(Presenter, LayoutTextAndWordsForAClass) {
  const app::PresenterLayout hd = app::presenter_layout(1920, 1080);
  EXPECT_EQ(hd.font, 36.0f);  // the panel's is 24 at this size
  EXPECT_EQ(hd.bed_right, 576.0f);
  const app::PresenterLayout small = app::presenter_layout(1280, 720);
  EXPECT_EQ(small.font, 24.0f);
  EXPECT_EQ(small.bed_right, 384.0f);
  EXPECT_GT(small.font, app::panel_layout(1280, 720).font);
  // A failure without the engine's words; what to do is kept.
  const std::string what = "the gas CFL number 1.046 passed 1 at t = 0.0001 s; reduce time.dt";
  const std::string plain = app::failure_for_a_class(what, 5.2, 2.8);
  EXPECT_EQ(plain.find("CFL"), std::string::npos) << plain;
  EXPECT_EQ(plain.find("time.dt"), std::string::npos) << plain;
  EXPECT_NE(plain.find("Press Reset to start again from the packed bed at U = 2.80 m/s"),
            std::string::npos)
      << plain;
  EXPECT_NE(app::failure_in_the_viewer(what, 5.2, 2.8).find("CFL"), std::string::npos);
  EXPECT_EQ(app::speed_for_a_class(1.0 / 2.3), "slow motion: 1 s of the bed takes 2.3 s here");
  EXPECT_EQ(app::speed_for_a_class(1.0), "real time");
  EXPECT_EQ(app::speed_for_a_class(0.0), "");
}

}  // namespace
}  // namespace fluidbed
