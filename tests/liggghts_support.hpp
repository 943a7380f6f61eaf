#pragma once
// Running LIGGGHTS (Debian's package, apt-get install liggghts) on an exported case, for the tests
// that compare fluidbed with its peer.
#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace fluidbed::testing {

inline std::optional<std::string> liggghts_binary() {
  if (const char* e = std::getenv("FLUIDBED_LIGGGHTS"); e && *e) return std::string(e);
  // Debian's package installs /usr/bin/liggghts; a LAMMPS-style build may be lmp_serial.
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin");
  for (std::string d; std::getline(dirs, d, ':');)
    for (const char* name : {"liggghts", "lmp_serial", "lmp_auto"})
      if (const std::filesystem::path p = std::filesystem::path(d) / name;
          std::filesystem::exists(p))
        return p.string();
  return std::nullopt;
}

struct LiggghtsRun {
  int status = -1;
  double wall_s = 0.0;
  std::string log;  // stdout and stderr
};

inline LiggghtsRun run_liggghts(const std::string& binary, const std::filesystem::path& dir) {
  const std::string cmd =
      "cd '" + dir.string() + "' && '" + binary + "' -in in.liggghts > run.out 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int raw = std::system(cmd.c_str());
  LiggghtsRun r;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.log = read_file(dir / "run.out");
  return r;
}

// The thermo rows (step atoms ke erot ke_total) of the log, in order.
inline std::vector<std::array<double, 5>> thermo_rows(const std::string& log) {
  std::istringstream in(log);
  std::vector<std::array<double, 5>> rows;
  bool in_table = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("Step") != std::string::npos && line.find("KinEng") != std::string::npos) {
      in_table = true;
      continue;
    }
    if (line.rfind("Loop time", 0) == 0) in_table = false;
    if (!in_table) continue;
    std::istringstream w(line);
    std::vector<double> row;
    for (double v; w >> v;) row.push_back(v);
    if (row.size() == 5) rows.push_back({row[0], row[1], row[2], row[3], row[4]});
  }
  return rows;
}

#define REQUIRE_LIGGGHTS(var)                                                   \
  const auto var = liggghts_binary();                                           \
  if (!var)                                                                     \
    GTEST_SKIP() << "LIGGGHTS is not installed (apt-get install liggghts), or " \
                    "set FLUIDBED_LIGGGHTS to its binary";

}  // namespace fluidbed::testing
