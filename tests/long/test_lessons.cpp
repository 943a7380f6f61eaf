// The shipped lessons (assets/lessons/) run whole, headlessly, as a teacher's machine without a
// display runs them into teaching videos: each exits 0 with DIR/video.mp4; the hysteresis
// lesson's live curve has both branches, the increasing one above the decreasing one at the
// same velocity below U_mf (the loop of Fig. 6), and U_mf from its decreasing branch. Minutes
// each: label long.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Lesson {
  int status = -1;
  std::string output;
  fs::path out;
};

Lesson run_lesson(const std::string& name) {
  Lesson l;
  l.out = fs::temp_directory_path() / ("fluidbed_lesson_" + name);
  fs::remove_all(l.out);
  fs::create_directories(l.out);
  const std::string log = (l.out / "log.txt").string();
  const std::string cmd = "env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(FLUIDBED_BINARY) +
                          " view --lesson " + name + " --frame-size 640x360 --out " +
                          (l.out / "out").string() + " > " + log + " 2>&1";
  const int raw = std::system(cmd.c_str());
  l.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  l.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return l;
}

// The lesson's last lines, from its "wrote ..." (all of it if it wrote nothing).
std::string tail(const std::string& output) {
  const std::size_t at = output.rfind("wrote ");
  return at == std::string::npos ? output : output.substr(at);
}

// One test per lesson, so that ctest runs them side by side on a machine with several cores.
void expect_video(const char* name) {
  const Lesson l = run_lesson(name);
  EXPECT_EQ(l.status, 0) << name << "\n" << l.output;
  EXPECT_TRUE(fs::exists(l.out / "out" / "video.mp4")) << name << "\n" << l.output;
  std::printf("%s: %s", name, tail(l.output).c_str());
}

TEST(Lessons, BubblesAndSlugsMakesItsVideo) { expect_video("bubbles-and-slugs"); }
TEST(Lessons, IdealVsRealMakesItsVideo) { expect_video("ideal-vs-real"); }
TEST(Lessons, SoftVsStiffMakesItsVideo) { expect_video("soft-vs-stiff"); }

TEST(Lessons, HysteresisBuildsTheLoopOfFig6) {
  const Lesson l = run_lesson("hysteresis");
  ASSERT_EQ(l.status, 0) << l.output;
  EXPECT_TRUE(fs::exists(l.out / "out" / "video.mp4"));
  EXPECT_TRUE(fs::exists(l.out / "out" / "hysteresis.png"));
  std::ifstream csv(l.out / "out" / "hysteresis.csv");
  std::string line;
  std::getline(csv, line);
  std::map<std::string, std::map<double, double>> branch;  // direction -> U -> mean dp
  while (std::getline(csv, line)) {
    std::istringstream row(line);
    std::string b, direction, u, dp;
    std::getline(row, b, ',');
    std::getline(row, direction, ',');
    std::getline(row, u, ',');
    std::getline(row, dp, ',');
    branch[direction][std::stod(u)] = std::stod(dp);
  }
  std::printf("%s", tail(l.output).c_str());
  // Every velocity held gave its point: 6 up (0.4 to 1.4 U_mf), 5 down (1.2 to 0.4).
  ASSERT_EQ(branch["increasing"].size(), 6u) << l.output;
  ASSERT_EQ(branch["decreasing"].size(), 5u) << l.output;
  // Below U_mf the packed bed going up holds more than the settled bed coming down (0.6 and 0.8
  // U_mf): the hysteresis.
  auto up = branch["increasing"].begin(), down = branch["decreasing"].begin();
  for (int k = 0; k < 3; ++k, ++up, ++down) {
    ASSERT_NEAR(up->first, down->first, 1e-9);
    if (k > 0) {
      EXPECT_GT(up->second, down->second) << "at " << up->first << " m/s";
    }
  }
  EXPECT_NE(l.output.find("U_mf from the decreasing branch"), std::string::npos) << l.output;
}

}  // namespace
