#pragma once
// Running `fluidbed view` from the tests: the program with its output captured, a fresh folder per
// test, PNGs read back, pixels counted; and a viewer in the background driven with a pointer and
// keys through xdotool (a virtual display: ctest runs these under xvfb-run).
#include <signal.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fluidbed::testing {

struct ViewRun {
  int status;
  std::string output;
};

// Runs `fluidbed view ARGS` with its output in DIR/log.txt (each test has its own folder: ctest
// runs them side by side).
inline ViewRun run_view(const std::filesystem::path& dir, const std::string& args,
                        const std::string& env = "") {
  const std::string log = (dir / "log.txt").string();
  const std::string cmd =
      env + " " + std::string(FLUIDBED_BINARY) + " view " + args + " > " + log + " 2>&1";
  const int raw = std::system(cmd.c_str());
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, text};
}

inline std::filesystem::path fresh_dir(const std::string& name) {
  // Per process: ctest runs this binary's tests side by side.
  const auto d = std::filesystem::temp_directory_path() /
                 ("fluidbed_view_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// Writes TEXT to P and returns P as a string (a command line's argument). Not test_support.hpp's
// write_file: the two are in one namespace, and one name with two return types in two test files
// is one function to the linker.
inline std::string written_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
  return p.string();
}

struct Png {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const {
    return rgb.data() + 3 * (static_cast<std::size_t>(y) * w + x);
  }
};

inline Png read_png(const std::string& path) {
  Png p;
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), &p.w, &p.h, &n, 3);
  if (data) {
    p.rgb.assign(data, data + static_cast<std::size_t>(p.w) * p.h * 3);
    stbi_image_free(data);
  }
  return p;
}

// Pixels of [x0, x1) x [y0, y1) for which `pred(r, g, b)` holds.
template <class P>
int count_pixels(const Png& p, int x0, int x1, int y0, int y1, P pred) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const unsigned char* c = p.at(x, y);
      n += pred(c[0], c[1], c[2]) ? 1 : 0;
    }
  return n;
}

// A viewer started in the background (its output in DIR/log.txt), the widgets' places in
// DIR/widgets.txt ($FLUIDBED_VIEW_WIDGETS).
struct BackgroundView {
  pid_t pid = -1;
  std::filesystem::path dir;

  // ENV: variable assignments for the viewer ("NAME=value ...").
  BackgroundView(const std::filesystem::path& folder, const std::string& args,
                 const std::string& env = "")
      : dir(folder) {
    const std::string cmd = env + " FLUIDBED_VIEW_WIDGETS=" + (dir / "widgets.txt").string() +
                            " exec " +
                            std::string(FLUIDBED_BINARY) + " view " + args + " > " +
                            (dir / "log.txt").string() + " 2>&1";
    pid = ::fork();
    if (pid == 0) {
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~BackgroundView() {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
  // "name x0 y0 x1 y1 value..." lines by name (the last write).
  std::map<std::string, std::vector<std::string>> widgets() const {
    std::map<std::string, std::vector<std::string>> out;
    std::ifstream in(dir / "widgets.txt");
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      std::vector<std::string> w;
      for (std::string x; words >> x;) w.push_back(x);
      if (!w.empty()) out[w[0]] = std::vector<std::string>(w.begin() + 1, w.end());
    }
    return out;
  }
  // Waits (up to `seconds`) until the widget `name` is listed; its fields, or empty.
  std::vector<std::string> wait_for_widget(const std::string& name, double seconds = 120.0) const {
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - t0 < std::chrono::duration<double>(seconds)) {
      const auto w = widgets();
      if (auto it = w.find(name); it != w.end() && it->second.size() >= 4) return it->second;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return {};
  }
  // Whether the viewer is still running (it has not exited).
  bool running() {
    int raw = 0;
    if (pid <= 0) return false;
    if (::waitpid(pid, &raw, WNOHANG) != pid) return true;
    pid = -1;
    return false;
  }
  // The fields of widget NAME once `pred(fields)` holds (up to `seconds`), or empty.
  template <class P>
  std::vector<std::string> wait_until(const std::string& name, P pred,
                                      double seconds = 120.0) const {
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - t0 < std::chrono::duration<double>(seconds)) {
      const auto w = widgets();
      if (auto it = w.find(name); it != w.end() && it->second.size() >= 4 && pred(it->second))
        return it->second;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return {};
  }
  // The exit status once the viewer ended (-1 after `seconds`).
  int wait(double seconds = 120.0) {
    const auto t0 = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - t0 < std::chrono::duration<double>(seconds)) {
      int raw = 0;
      if (::waitpid(pid, &raw, WNOHANG) == pid) {
        pid = -1;
        return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return -1;
  }
  std::string log() const {
    std::ifstream in(dir / "log.txt");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

// xdotool ARGS on the test's display (the window sits at the screen's top left: no window
// manager under Xvfb); true when it ran.
inline bool xdotool(const std::string& args) {
  return std::system(("xdotool " + args + " > /dev/null 2>&1").c_str()) == 0;
}
inline bool have_xdotool() {
  return std::system("command -v xdotool > /dev/null 2>&1") == 0;
}

// Skips a test without a display (or fails it where ctest requires one, under xvfb-run).
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

inline double number(const std::vector<std::string>& w, std::size_t k) {
  return std::stod(w.at(k));
}

// "viewer: stopped at t = T s, step N, U = U m/s": the engine where the window closed.
struct Final {
  double t = -1.0, u = -1.0;
  long long steps = -1;
};
inline Final final_state(const std::string& log) {
  Final f;
  const auto at = log.find("viewer: stopped at t = ");
  if (at != std::string::npos)
    std::sscanf(log.c_str() + at, "viewer: stopped at t = %lf s, step %lld, U = %lf", &f.t,
                &f.steps, &f.u);
  return f;
}

// The window mapped and drawing before the pointer acts on it (its first frames come before the
// display has given it the pointer).
inline void settle_window() {
  std::this_thread::sleep_for(std::chrono::seconds(1));
}

// The window's pixel at the middle of widget W ("x y" for xdotool).
inline std::string middle_of(const std::vector<std::string>& w) {
  return std::to_string(static_cast<int>(0.5 * (number(w, 0) + number(w, 2)))) + " " +
         std::to_string(static_cast<int>(0.5 * (number(w, 1) + number(w, 3))));
}

// Points at the middle of widget W, lets the window see the pointer there, and clicks; true when
// xdotool ran.
inline bool click_middle_of(const std::vector<std::string>& w) {
  if (!xdotool("mousemove " + middle_of(w))) return false;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  return xdotool("click 1");
}

}  // namespace fluidbed::testing
