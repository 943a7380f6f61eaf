#include "cli/bench_peer.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "io/liggghts_export.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

namespace fluidbed::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::optional<std::string> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string d; std::getline(dirs, d, ':');) {
    if (d.empty()) continue;
    const fs::path p = fs::path(d) / name;
    if (::access(p.c_str(), X_OK) == 0) return p.string();
  }
  return std::nullopt;
}

int exit_status(int raw) {
  return raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// LIGGGHTS' binary: $FLUIDBED_LIGGGHTS, else `liggghts` on PATH, else installed (root only).
std::string liggghts_binary() {
  if (const char* e = std::getenv("FLUIDBED_LIGGGHTS"); e && *e) {
    if (::access(e, X_OK) != 0)
      throw InputError(std::string("FLUIDBED_LIGGGHTS=") + e + ": not an executable file");
    return e;
  }
  if (auto p = find_on_path("liggghts")) return *p;
  if (::geteuid() != 0)
    throw InputError(
        "bench --peer liggghts: LIGGGHTS is not installed; install it with `sudo apt-get "
        "install -y liggghts` (Debian's LIGGGHTS 3.8), or set FLUIDBED_LIGGGHTS to its binary");
  std::printf("LIGGGHTS is not installed: apt-get install -y liggghts\n");
  std::fflush(stdout);
  const int raw = std::system(
      "DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liggghts > /dev/null 2>&1 || "
      "(apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liggghts "
      "> /dev/null 2>&1)");
  if (exit_status(raw) == 0)
    if (auto p = find_on_path("liggghts")) return *p;
  throw InputError(
      "bench --peer liggghts: `apt-get install -y liggghts` failed; install LIGGGHTS 3.8 and "
      "retry");
}

// What LIGGGHTS' log says about the run it did.
struct LiggghtsLog {
  std::string version;               // "LIGGGHTS-PUBLIC 3.8.0"
  double loop_s = 0.0;               // sum of its "Loop time of" lines, s
  std::int64_t steps = 0;            // sum of their step counts
  long long atoms = -1;              // of the last loop
  int procs = 0;                     // of the last loop
  int loops = 0;                     // "Loop time" lines (one per run command)
  std::vector<double> dt;            // every timestep command, s
  long long last_thermo_atoms = -1;  // the "atoms" column of the last thermo row
};

LiggghtsLog parse_liggghts_log(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SimulationFailure("LIGGGHTS wrote no log (" + path + ")");
  LiggghtsLog log;
  bool in_thermo = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("LIGGGHTS (Version ", 0) == 0) {
      const auto close = line.find(',');
      log.version = line.substr(18, close == std::string::npos ? std::string::npos : close - 18);
      continue;
    }
    double loop = 0.0;
    int procs = 0;
    long long steps = 0, atoms = 0;
    if (std::sscanf(line.c_str(), "Loop time of %lf on %d procs for %lld steps with %lld atoms",
                    &loop, &procs, &steps, &atoms) == 4) {
      log.loop_s += loop;
      log.steps += steps;
      log.atoms = atoms;
      log.procs = procs;
      ++log.loops;
      in_thermo = false;
      continue;
    }
    std::istringstream words(line);
    std::string first;
    words >> first;
    if (first == "timestep") {
      double dt = 0.0;
      if (words >> dt) log.dt.push_back(dt);
    } else if (first == "Step") {
      in_thermo = line.find("Atoms") != std::string::npos;
    } else if (in_thermo) {
      long long step = 0, n = 0;
      std::istringstream row(line);
      if (row >> step >> n) log.last_thermo_atoms = n;
    }
  }
  return log;
}

// The last line of a file that mentions ERROR (LIGGGHTS' own words), or its last line.
std::string error_line(const std::string& path) {
  std::ifstream in(path);
  std::string last, error;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) last = line;
    if (line.find("ERROR") != std::string::npos) error = line;
  }
  return error.empty() ? last : error;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path.string());
  return nlohmann::json::parse(in);
}

}  // namespace

int bench_peer_command(const RunArgs& a, const std::string& peer) {
  if (peer != "liggghts")
    throw InputError("--peer \"" + peer + "\": unknown peer; known: liggghts");
  const std::string scene = a.scene.empty() ? asset_dir() + "/scenes/packing.toml" : a.scene;
  Settings s = load_scene(scene, a.overrides);
  refuse_unsafe_scene(s);
  if (s.particles.placement == Placement::Packed)
    throw InputError(
        "bench --peer liggghts: particles.placement \"packed\": the deck makes the packing "
        "first while fluidbed starts from its cache, not the same work; bench a lattice or "
        "state start (e.g. assets/scenes/packing.toml)");
  if (a.until >= 0.0) s.time.end = a.until;
  const std::string binary = liggghts_binary();
  const std::string out = a.out.empty() ? "out/bench" : a.out;
  const fs::path deck_dir = fs::path(out) / "liggghts";
  const LiggghtsCase deck = write_liggghts_case(s, deck_dir.string());  // refusals come first
  std::error_code ignore;
  fs::remove(deck_dir / "log.liggghts", ignore);  // never read a stale log

  // fluidbed on the deck's work: the gas left out as the deck leaves it out.
  RunArgs f = a;
  f.scene = scene;
  f.overrides.push_back("gas.enabled=false");
  f.overrides.push_back("diagnostics.probes=[]");  // a scene's pressure probes go with the gas
  f.until = s.time.end;
  f.out = out;
  std::printf("fluidbed, on the work of the LIGGGHTS deck (the gas left out, as in the deck):\n");
  std::fflush(stdout);
  const auto f0 = Clock::now();
  bench_command(f);
  const double fluidbed_total = seconds_since(f0);
  const fs::path bench_path = fs::path(out) / "bench.json";
  nlohmann::json bench = read_json(bench_path);

  std::printf("\nLIGGGHTS (%s, one process) on %s ...\n", binary.c_str(), deck.deck.c_str());
  std::fflush(stdout);
  const std::string screen = (deck_dir / "liggghts.out").string();
  const std::string cmd = "cd " + shell_quote(deck_dir.string()) + " && " + shell_quote(binary) +
                          " -in in.liggghts -log log.liggghts > liggghts.out 2>&1";
  const auto l0 = Clock::now();
  const int status = exit_status(std::system(cmd.c_str()));
  const double liggghts_process = seconds_since(l0);
  if (status != 0)
    throw SimulationFailure("LIGGGHTS failed (exit status " + std::to_string(status) +
                            "): " + error_line(screen) + " (see " + screen + ")");
  const LiggghtsLog log = parse_liggghts_log((deck_dir / "log.liggghts").string());
  if (log.loops == 0 || log.loop_s <= 0.0)
    throw SimulationFailure("LIGGGHTS' log has no \"Loop time\" line (see " + screen + ")");

  // The same work: particles, steps, dt and end time.
  const long long particles = bench["particles"].get<long long>();
  const std::int64_t steps = bench["steps"].get<std::int64_t>();
  const double end = bench["sim_time_s"].get<double>();
  const double l_dt = log.dt.empty() ? std::numeric_limits<double>::quiet_NaN() : log.dt.back();
  bool one_dt = !log.dt.empty();
  for (double d : log.dt) one_dt = one_dt && d == log.dt.front();
  const double l_end = static_cast<double>(log.steps) * l_dt;
  std::string differs;
  if (log.atoms != particles || log.last_thermo_atoms != particles)
    differs += " particles " + std::to_string(particles) + " vs " + std::to_string(log.atoms) +
               " (last thermo row: " + std::to_string(log.last_thermo_atoms) + ");";
  if (log.steps != steps)
    differs += " steps " + std::to_string(steps) + " vs " + std::to_string(log.steps) + ";";
  if (!one_dt || l_dt != s.time.dt) differs += " dt differs;";
  if (!(std::fabs(l_end - end) <= 1e-9 * std::max(1.0, end))) differs += " end time differs;";
  if (!differs.empty())
    throw SimulationFailure("bench --peer liggghts: not the same work (fluidbed vs LIGGGHTS):" +
                            differs + " see " + (deck_dir / "log.liggghts").string());

  const double work = static_cast<double>(particles) * static_cast<double>(steps);
  const double f_loop = bench["wall_time_s"].get<double>();
  const double f_rate = f_loop > 0.0 ? work / f_loop : 0.0;
  const double f_rate_total = work / fluidbed_total;
  const double l_rate = work / log.loop_s;
  const double l_rate_total = work / liggghts_process;
  const double ratio = f_rate / l_rate, ratio_total = f_rate_total / l_rate_total;
  const int threads = bench["threads"].get<int>();

  std::printf(
      "same work in both: %lld particles, %lld steps of %g s to %g s (checked from "
      "LIGGGHTS' log: %d run, \"for %lld steps with %lld atoms\", timestep %g); the gas "
      "left out of both\n",
      particles, static_cast<long long>(steps), s.time.dt, end, log.loops,
      static_cast<long long>(log.steps), log.atoms, l_dt);
  std::printf("                        %12s %12s\n", "fluidbed", "LIGGGHTS");
  std::printf(
      "loop wall time (s)      %12.4g %12.4g   (fluidbed's step loop; LIGGGHTS' "
      "\"Loop time\")\n",
      f_loop, log.loop_s);
  std::printf("whole run wall (s)      %12.4g %12.4g   (setup included: %.3g s, %.3g s)\n",
              fluidbed_total, liggghts_process, fluidbed_total - f_loop,
              liggghts_process - log.loop_s);
  std::printf("particle-steps/s        %12.4g %12.4g   (loops)\n", f_rate, l_rate);
  std::printf("particle-steps/s, whole %12.4g %12.4g\n", f_rate_total, l_rate_total);
  std::printf("threads / processes     %12d %12d\n", threads, log.procs);
  std::printf(
      "ratio fluidbed / LIGGGHTS in particle-steps/s: %.3g (loops), %.3g (whole runs)"
      "; above 1: fluidbed faster\n",
      ratio, ratio_total);

  bench["peer"] = {
      {"code", "liggghts"},
      {"version", log.version},
      {"binary", binary},
      {"deck", deck.deck},
      {"log", (deck_dir / "log.liggghts").string()},
      {"processes", log.procs},
      {"same_work", true},
      {"gas", "left out of both (LIGGGHTS is DEM only)"},
      {"work",
       {{"particles", particles}, {"steps", steps}, {"dt_s", s.time.dt}, {"end_time_s", end}}},
      {"fluidbed",
       {{"particles", particles},
        {"steps", steps},
        {"dt_s", s.time.dt},
        {"end_time_s", end},
        {"loop_wall_s", f_loop},
        {"total_wall_s", fluidbed_total},
        {"setup_s", fluidbed_total - f_loop},
        {"particle_steps_per_s", f_rate},
        {"particle_steps_per_s_total", f_rate_total},
        {"threads", threads}}},
      {"liggghts",
       {{"particles", log.atoms},
        {"steps", log.steps},
        {"dt_s", l_dt},
        {"end_time_s", l_end},
        {"loop_wall_s", log.loop_s},
        {"process_wall_s", liggghts_process},
        {"setup_s", liggghts_process - log.loop_s},
        {"particle_steps_per_s", l_rate},
        {"particle_steps_per_s_total", l_rate_total}}},
      {"ratio", ratio},
      {"ratio_total", ratio_total},
  };
  write_file_atomically(bench_path.string(), [&](std::ostream& o) { o << bench.dump(2) << "\n"; });
  std::printf("wrote %s (with \"peer\")\n", bench_path.string().c_str());
  return 0;
}

}  // namespace fluidbed::app
