// A soak test of the viewer's engine side (no window): the teaching scene, as `fluidbed view`
// opens it, driven by random commands at random times for as long as FLUIDBED_SOAK_SECONDS says
// (else FLUIDBED_SOAK_DEFAULT_SECONDS, which ctest sets: 4 minutes in the README's test command,
// half an hour in the extended runs; else ten minutes), as a class would drive it: the gas
// velocity anywhere on the panel's slider, the ideal case on and off, reset, pause, run, single
// steps, the bubble outlines, and a reader thread standing in for the window that colours every
// new snapshot by a randomly chosen quantity. It must never fail
// (no engine error, no refused command, every snapshot whole and finite) and its memory must stay
// flat: after the first minute, each minute's mean resident size stays within 5 % of the first
// minute's peak (and no single reading passes it by 15 %). The memory is read only while no
// command is being applied: a reset or a switch of the contact model builds the new simulation
// before it lets the old one go (ViewModel::reset, rebuild_keeping_state: a build that fails
// leaves the running bed as it was), so for the milliseconds it takes two simulations are
// resident, a transient and not growth. The commands come from a seeded generator
// (FLUIDBED_SOAK_SEED; the seed is printed).
#include <gtest/gtest.h>

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "render/colour_map.hpp"
#include "render/colour_modes.hpp"
#include "scene/scene_loader.hpp"
#include "view/engine.hpp"

namespace fluidbed {
namespace {

using app::ViewCommand;
using app::ViewEngine;
using K = ViewCommand::Kind;
using Clock = std::chrono::steady_clock;

double env_or(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtod(v, nullptr) : fallback;
}

// Resident set size of this process (bytes), from /proc/self/statm, after handing the pages
// malloc holds free back to the system (malloc_trim): the memory in use, not the allocator's
// high-water mark of transient buffers.
double resident_bytes() {
  malloc_trim(0);
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

TEST(ViewSoak, RandomCommandsNeitherFailNorGrow) {
  const double seconds =
      env_or("FLUIDBED_SOAK_SECONDS", env_or("FLUIDBED_SOAK_DEFAULT_SECONDS", 600.0));
  const auto seed = static_cast<std::uint32_t>(env_or("FLUIDBED_SOAK_SEED", 20261202.0));
  std::printf("soak: %.0f s of random commands, seed %u (FLUIDBED_SOAK_SEED)\n", seconds, seed);
  // One engine thread: the reader thread takes the other core, as the window does.
  Settings scene = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/teaching.toml");
  scene.threads = 1;
  // The panel's slider reaches 2.5 U_mf (window.cpp); the paper's U_mf is 1.8 m/s.
  const double velocity_top = 2.5 * 1.8;

  ViewEngine engine(scene, ViewEngine::Options{});
  engine.start();

  std::atomic<bool> stop{false};
  std::atomic<long> frames{0}, bad_frames{0};
  std::thread viewer([&] {
    std::mt19937 pick(seed + 1);
    const auto modes = render::colour_by_names();
    std::uint64_t last_seq = 0;
    while (!stop.load()) {
      std::uint64_t seq = 0;
      auto snap = engine.snapshots().latest(&seq);
      (void)engine.take_samples();
      (void)engine.status();
      if (!snap || seq == last_seq) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        continue;
      }
      last_seq = seq;
      // "Drawing": one colour per particle, by a quantity the user picked.
      const render::ColourBy by = render::parse_colour_by(
          modes[std::uniform_int_distribution<std::size_t>(0, modes.size() - 1)(pick)]);
      const render::ColourScale scale = render::colour_scale(by, *snap, 0.0, 0.0, 8);
      double sum = 0.0;
      for (std::size_t i = 0; i < snap->particles(); ++i) {
        const double at = render::scale_position(scale, render::particle_value(by, *snap, i));
        sum += at + snap->x[i] + snap->y[i];
        if (!(at >= 0.0 && at <= 1.0)) sum = NAN;
      }
      for (double u : snap->gas_ux) sum += u;
      if (snap->particles() != 2400 || !std::isfinite(sum)) ++bad_frames;
      ++frames;
      std::this_thread::sleep_for(std::chrono::milliseconds(16));  // about 60 frames a second
    }
  });

  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto t0 = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  // The "first minute": a tenth of the run, at least 30 s (a shortened soak's process grows to
  // its working size over its first half minute) and at most 60 s.
  const double settle = std::min(60.0, std::max(30.0, seconds / 10.0));
  double first_peak = 0.0, later_peak = 0.0;
  std::vector<double> window_sum;  // resident size summed over each later "minute"
  std::vector<int> window_n;
  long commands = 0, resets = 0;
  std::uint64_t posted = 0;  // the commands posted so far (ViewEngine::post's count)
  const double report_every = settle / 2.0;
  double next_report = 0.0;
  Clock::time_point next_sample{};  // the memory is read once a second
  std::string failure;
  while (elapsed() < seconds && failure.empty()) {
    const double r = unit(rng);
    ViewCommand c;
    if (r < 0.35) {
      c = {K::velocity, velocity_top * unit(rng)};
    } else if (r < 0.45) {
      c = {K::ideal, unit(rng) < 0.5 ? 1.0 : 0.0};
    } else if (r < 0.52) {
      c = {K::reset, 0.0};
      ++resets;
    } else if (r < 0.62) {
      c = {K::pause, 0.0};
    } else if (r < 0.70) {
      c = {K::step, std::floor(1.0 + 50.0 * unit(rng))};
    } else if (r < 0.80) {
      c = {K::bubbles, unit(rng) < 0.5 ? 1.0 : 0.0};
    } else {
      c = {K::run, 0.0};
    }
    posted = engine.post(c);
    ++commands;
    // The next command after 0.05 to 3 s (some in quick bursts, as clicks come).
    const double wait = unit(rng) < 0.2 ? 0.05 : 0.05 + 2.95 * unit(rng);
    const auto until = Clock::now() + std::chrono::duration<double>(wait);
    while (Clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      const app::EngineStatus st = engine.status();
      if (!st.error.empty()) failure = "engine failure: " + st.error;
      if (!st.refusal.empty()) failure = "refused command: " + st.refusal;
      if (Clock::now() < next_sample || st.commands_applied != posted) continue;
      const double rss = resident_bytes();
      // Applied before and after the reading: no command was in the engine's hands meanwhile.
      if (engine.status().commands_applied != posted) continue;
      next_sample = Clock::now() + std::chrono::seconds(1);
      if (elapsed() >= next_report) {  // the memory's course, for a failure's reader
        std::printf("soak: t = %5.0f s  resident %.1f MB\n", elapsed(), rss / 1e6);
        std::fflush(stdout);
        next_report += report_every;
      }
      const double at = elapsed();
      (at < settle ? first_peak : later_peak) = std::max(at < settle ? first_peak : later_peak, rss);
      if (at >= settle) {  // the mean of each later "minute"
        const auto k = static_cast<std::size_t>(at / settle) - 1;
        if (window_sum.size() <= k) {
          window_sum.resize(k + 1, 0.0);
          window_n.resize(k + 1, 0);
        }
        window_sum[k] += rss;
        ++window_n[k];
      }
    }
  }
  stop.store(true);
  viewer.join();
  const app::EngineStatus st = engine.status();
  engine.stop();
  std::printf(
      "soak: %ld commands (%ld resets), %ld frames, simulated %.2f s in generation %llu; "
      "resident peak %.1f MB in the first %.0f s, %.1f MB after\n",
      commands, resets, frames.load(), st.time, static_cast<unsigned long long>(st.generation),
      first_peak / 1e6, settle, later_peak / 1e6);
  EXPECT_TRUE(failure.empty()) << failure << " (seed " << seed << ")";
  EXPECT_EQ(bad_frames.load(), 0);
  EXPECT_GT(frames.load(), 0);
  EXPECT_GT(commands, 10);
  EXPECT_GT(first_peak, 0.0);
  // Flat: every later minute's mean resident size within 5 % of the first minute's peak. The
  // size read once a second swings by about 0.5 MB of 12 MB (snapshots and gas buffers in flight
  // when it is read), so single readings get a looser bound; a leak of one snapshot per command
  // (about 0.2 MB, 45 commands a minute) breaks both within two minutes.
  for (std::size_t k = 0; k < window_sum.size(); ++k) {
    if (window_n[k] == 0) continue;
    const double mean = window_sum[k] / window_n[k];
    const double from = settle * static_cast<double>(k + 1);
    std::printf("soak: %4.0f to %4.0f s: mean resident %.2f MB\n", from,
                from + settle, mean / 1e6);
    EXPECT_LE(mean, 1.05 * first_peak) << "memory grew in minute " << k + 2 << " (seed " << seed << ")";
  }
  EXPECT_LE(later_peak, 1.15 * first_peak)
      << "memory grew after the first " << settle << " s (seed " << seed << ")";
}

}  // namespace
}  // namespace fluidbed
