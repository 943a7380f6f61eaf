#pragma once
// Small helpers shared by the test binaries.
#include <signal.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <thread>
#include <vector>
#include <string>

#include <unistd.h>
#include <fstream>
#include <string>

#include "core/errors.hpp"
#include "dem/dem_solver.hpp"
#include "scene/scene_loader.hpp"
#include "scene/settings.hpp"

namespace fluidbed::testing {

constexpr double kPi = 3.14159265358979323846;

// The one-line error a scene text with overrides is refused with ("" when it loads).
inline std::string scene_error(const std::string& text,
                               const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, "t.toml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The paper's particle (D = 4 mm, rho = 2700 kg/m^3).
inline double paper_mass() { return 2700.0 * kPi * 0.004 * 0.004 * 0.004 / 6.0; }

// Restitution of a linear spring-dashpot contact of effective mass m (closed form).
inline double analytic_restitution(double k, double eta, double m) {
  const double zeta = eta / (2.0 * std::sqrt(k * m));
  return std::exp(-kPi * zeta / std::sqrt(1.0 - zeta * zeta));
}

// A single particle at (x, y) with velocity (vx, vy): the drop and rolling scenes.
inline Settings single_particle(double x, double y, double vx = 0.0, double vy = 0.0) {
  Settings s;
  s.scene.kind = SceneKind::Drop;
  s.particles.count = 1;
  s.particles.placement = Placement::Single;
  s.particles.x = x;
  s.particles.y = y;
  s.particles.vx = vx;
  s.particles.vy = vy;
  return s;
}

// Particles of the paper's size at given positions and velocities, for solver-level tests.
inline Particles make_particles(std::initializer_list<std::array<double, 5>> xyvw,
                                double diameter = 0.004, double density = 2700.0) {
  Particles p;
  p.resize(xyvw.size());
  std::size_t i = 0;
  for (const auto& q : xyvw) {
    p.set_sphere(i, diameter, density);
    p.x[i] = q[0];
    p.y[i] = q[1];
    p.vx[i] = q[2];
    p.vy[i] = q[3];
    p.w[i] = q[4];
    ++i;
  }
  return p;
}

// A fresh folder under the system temp dir.
// A fresh folder for this test process: ctest runs tests of one binary side by side in separate
// processes, so the process id keeps two of them from sharing (and deleting) each other's files.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("fluidbed-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// 300 spheres of the paper on a lattice 6 cm tall in a box 0.3 m high, landing on the jet (gas
// stepped every 20 particle steps): by 0.12 s (8000 steps, 0.15 s of wall time) dp carries 40 %
// of the bed's weight and 70 contacts hold history. Averages from 0.04 s.
inline std::string small_jet_bed_toml(const std::string& name) {
  return "[scene]\nname = \"" + name + R"("
kind = "bed"

[particles]
count = 300
placement = "lattice"
fill_height = 0.06
seed = 7

[domain]
height = 0.3

[gas]
cells_y = 15

[inlet]
kind = "jet"
superficial_velocity = 2.5

[coupling]
particle_steps_per_gas_step = 20

[time]
end = 0.12

[diagnostics]
output_interval = 1e-3
averaging_start = 0.04
)";
}

// Runs the fluidbed binary with arguments; returns the exit status and what it printed on stderr.
struct CommandResult {
  int status;
  std::string err;
  std::string out;
};
inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
inline CommandResult run_fluidbed(const std::string& args, const std::string& tag) {
  const auto dir = temp_dir("cmd-" + tag);
  const std::string cmd = std::string(FLUIDBED_BINARY) + " " + args + " > " +
                          (dir / "out.txt").string() + " 2> " + (dir / "err.txt").string();
  const int raw = std::system(cmd.c_str());
  const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return {status, read_file(dir / "err.txt"), read_file(dir / "out.txt")};
}

// One line of a CSV file: its values, quotes removed ("" inside quotes is a quote).
inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
        cur += '"';
        ++k;
      } else if (c == '"') {
        quoted = false;
      } else {
        cur += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// `fluidbed ARGS` in the background (its stdout in DIR/out.txt, its stderr in DIR/err.txt), sent
// SIGNAL (SIGTERM unless told) as soon as `ready()` says so (asked every 20 ms). Its exit status, and whether the
// signal was sent before it ended by itself.
struct TerminatedRun {
  int status = -1;  // -1: ended by a signal
  bool terminated = false;
};
inline TerminatedRun fluidbed_terminated(const std::string& args, const std::filesystem::path& dir,
                                         const std::function<bool()>& ready,
                                         int sig = SIGTERM) {
  const std::string cmd = "exec \"" + std::string(FLUIDBED_BINARY) + "\" " + args + " > \"" +
                          (dir / "out.txt").string() + "\" 2> \"" + (dir / "err.txt").string() +
                          "\"";
  TerminatedRun r;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  if (pid < 0) return r;
  int raw = 0;
  while (::waitpid(pid, &raw, WNOHANG) == 0) {
    if (ready()) {
      ::kill(pid, sig);
      r.terminated = true;
      ::waitpid(pid, &raw, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

// For fluidbed_terminated: true once `seconds` have passed since it was made.
inline std::function<bool()> after_seconds(double seconds) {
  const auto start = std::chrono::steady_clock::now();
  return [=] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
           seconds;
  };
}

}  // namespace fluidbed::testing
