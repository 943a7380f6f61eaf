// The view script (view/script.hpp): its words parsed, its errors naming the line, and the one
// interpreter (view/script_runner.hpp) that hands each line to the window or the headless viewer.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/errors.hpp"
#include "view/script.hpp"
#include "view/script_runner.hpp"
#include "view_scene.hpp"

namespace fluidbed {
namespace {
// ---------------------------------------------------------------------------------------------
// The view script.

TEST(ViewScript, ParsesEveryCommand) {
  const auto lines = app::parse_view_script(R"(
# a demo
at 0.05 velocity 1.8   # faster
ideal on
step 3
wait 0.5
colour mixing
gas-arrows off
bubbles on
track 12
track off
zoom 2.5
screenshot out/a.png
record out/v.mp4
record stop
at 0.1 quit
)",
                                            "demo.txt")
                         .lines;
  ASSERT_EQ(lines.size(), 14u);
  EXPECT_EQ(lines[0].at, 0.05);
  EXPECT_EQ(lines[0].kind, app::ScriptLine::Kind::velocity);
  EXPECT_EQ(lines[0].number, 1.8);
  EXPECT_EQ(lines[0].line, 3);
  EXPECT_EQ(lines[1].at, -1.0);
  EXPECT_EQ(lines[1].number, 1.0);
  EXPECT_EQ(lines[2].number, 3.0);
  EXPECT_EQ(lines[4].text, "mixing");
  EXPECT_EQ(lines[5].number, 0.0);
  EXPECT_EQ(lines[6].kind, app::ScriptLine::Kind::bubbles);
  EXPECT_EQ(lines[6].number, 1.0);
  EXPECT_EQ(lines[7].number, 12.0);
  EXPECT_EQ(lines[8].number, -1.0);
  EXPECT_EQ(lines[10].text, "out/a.png");
  EXPECT_EQ(lines[11].kind, app::ScriptLine::Kind::record);
  EXPECT_EQ(lines[12].kind, app::ScriptLine::Kind::record_stop);
  EXPECT_EQ(lines[13].kind, app::ScriptLine::Kind::quit);
  EXPECT_EQ(lines[13].at, 0.1);
}

TEST(ViewScript, NamesTheLineAndTheProblem) {
  const auto message = [](const std::string& text) {
    return testing::script_error(app::parse_view_script, text);
  };
  EXPECT_NE(message("run\njump 3\n").find("s.txt line 2: unknown command 'jump'"),
            std::string::npos)
      << message("run\njump 3\n");
  EXPECT_NE(message("velocity fast").find("line 1"), std::string::npos);
  EXPECT_NE(message("velocity -1").find(">= 0"), std::string::npos);
  EXPECT_NE(message("at x quit").find("'at'"), std::string::npos);
  EXPECT_NE(message("ideal maybe").find("on or off"), std::string::npos);
  EXPECT_NE(message("colour rainbow").find("unknown colour mode 'rainbow'"), std::string::npos);
  EXPECT_NE(message("colour rainbow").find("depth"), std::string::npos);  // a thick bed's mode
  EXPECT_EQ(app::parse_view_script("colour depth\n", "d.txt").lines.at(0).text, "depth");
  EXPECT_NE(message("quit now").find("unexpected 'now'"), std::string::npos);
  EXPECT_NE(message("step 0").find("whole count"), std::string::npos);
  EXPECT_NE(message("particles 0.003").find("density"), std::string::npos);
  EXPECT_NE(message("particles -1 2700").find("diameter must be > 0"), std::string::npos);
  const auto p = app::parse_view_script("particles 0.003 2500\nparticles scene\n", "p.txt").lines;
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].kind, app::ScriptLine::Kind::particles);
  EXPECT_EQ(p[0].number, 0.003);
  EXPECT_EQ(p[0].density, 2500.0);
  EXPECT_EQ(p[1].number, 0.0);
  EXPECT_EQ(p[1].density, 0.0);
  EXPECT_THROW(app::load_view_script("/nonexistent/script.txt"), InputError);
}

// The one interpreter: lines in order, each `at T` asked for once and waited for, commands a side
// does not carry out handed to unsupported(), nothing after quit.
TEST(ScriptRunner, WaitsForEachAtAndHandsEveryCommandOver) {
  struct Recorder : app::ScriptTarget {
    std::vector<std::string> calls;
    double engine_time = 0.0, target_time = 0.0;  // s
    bool quitting = false;
    void run_to(double t) override {
      target_time = t;
      calls.push_back("run_to " + std::to_string(t));
    }
    bool busy() override { return engine_time < target_time; }
    bool stopped() const override { return quitting; }
    void unsupported(const app::ScriptLine& l) override {
      calls.push_back("unsupported line " + std::to_string(l.line));
    }
    bool velocity(double u) override {
      calls.push_back("velocity " + std::to_string(u));
      return true;
    }
    bool quit() override {
      quitting = true;
      calls.push_back("quit");
      return true;
    }
  };
  app::ScriptRunner runner(
      app::parse_view_script("velocity 1\nat 0.5 velocity 2\nzoom 2\nquit\nvelocity 3\n", "t")
          .lines);
  Recorder r;
  runner.advance(r);  // the first line, then the engine must get to 0.5 s
  EXPECT_EQ(r.calls, (std::vector<std::string>{"velocity 1.000000", "run_to 0.500000"}));
  runner.advance(r);  // still on its way: nothing more, and the `at` is not asked for again
  EXPECT_EQ(r.calls.size(), 2u);
  r.engine_time = 0.5;
  runner.advance(r);
  EXPECT_EQ(r.calls, (std::vector<std::string>{"velocity 1.000000", "run_to 0.500000",
                                               "velocity 2.000000", "unsupported line 3", "quit"}));
  EXPECT_FALSE(runner.at_end());  // the line after quit is never carried out
}

}  // namespace
}  // namespace fluidbed
