// The viewer's engine side: the snapshot hand-off between threads, the command queue, the engine
// thread (pause, single step, gas velocity, reset, the ideal case) and the view script parser.
// Built also under the thread sanitizer (scripts/test.sh): the engine thread and a reader thread
// standing in for the window run together here. Also the script runner, on a recording target.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "core/errors.hpp"
#include "sim/snapshot.hpp"
#include "view/engine.hpp"
#include "view_scene.hpp"

namespace fluidbed {
namespace {

using app::ViewCommand;
using app::ViewEngine;
using K = ViewCommand::Kind;
using namespace std::chrono_literals;

constexpr auto kTimeout = 120s;  // generous: the sanitizer builds are slow

// ---------------------------------------------------------------------------------------------
// The snapshot hand-off.

TEST(SnapshotChannel, ReaderGetsTheNewestAndKeepsWhatItHolds) {
  SnapshotChannel ch;
  EXPECT_EQ(ch.latest(), nullptr);
  auto a = ch.acquire();
  a->time = 1.0;
  a->x.assign(10, 1.0);
  ch.publish(a);
  std::uint64_t seq = 0;
  auto held = ch.latest(&seq);
  EXPECT_EQ(seq, 1u);
  ASSERT_NE(held, nullptr);
  a.reset();
  // The writer goes on: the buffer the reader holds is never handed back for filling.
  for (int k = 2; k <= 5; ++k) {
    auto b = ch.acquire();
    EXPECT_NE(b.get(), held.get());
    b->time = k;
    b->x.assign(10, static_cast<double>(k));
    ch.publish(b);
  }
  EXPECT_EQ(held->time, 1.0);
  EXPECT_EQ(held->x[9], 1.0);
  auto newest = ch.latest(&seq);
  EXPECT_EQ(seq, 5u);
  EXPECT_EQ(newest->time, 5.0);
}

TEST(SnapshotChannel, ReusesTheSpareBufferWhenNoReaderHoldsIt) {
  SnapshotChannel ch;
  Snapshot* first = nullptr;
  {
    auto a = ch.acquire();
    first = a.get();
    ch.publish(a);
  }
  ch.publish(ch.acquire());  // the first becomes the spare
  auto c = ch.acquire();
  EXPECT_EQ(c.get(), first);  // no reader: no allocation per publish
}

// A writer thread publishing snapshots whose every value says which one it is, a reader thread
// taking the newest: a reader never sees a half-written snapshot, and the sequence never goes
// back. (Under TSan this is the hand-off's race check.)
TEST(SnapshotChannel, ConcurrentWriterAndReaderSeeWholeSnapshots) {
  SnapshotChannel ch;
  constexpr int kPublishes = 3000;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (int k = 1; k <= kPublishes; ++k) {
      auto s = ch.acquire();
      s->time = k;
      s->x.assign(256, static_cast<double>(k));
      s->y.assign(256, static_cast<double>(-k));
      ch.publish(std::move(s));
    }
    done.store(true);
  });
  std::uint64_t last = 0;
  int torn = 0, reads = 0;
  while (!done.load() || last < kPublishes) {
    std::uint64_t seq = 0;
    auto s = ch.latest(&seq);
    if (!s) continue;
    ++reads;
    EXPECT_GE(seq, last);
    last = seq;
    for (std::size_t i = 0; i < s->x.size(); ++i)
      torn += (s->x[i] != s->time || s->y[i] != -s->time) ? 1 : 0;
    if (done.load() && seq == kPublishes) break;
  }
  writer.join();
  EXPECT_EQ(torn, 0);
  EXPECT_GT(reads, 0);
  EXPECT_EQ(ch.latest()->time, kPublishes);
}

// ---------------------------------------------------------------------------------------------
// The command queue.

TEST(CommandQueue, KeepsOrderAndWakesAWaitingTaker) {
  app::CommandQueue q;
  EXPECT_TRUE(q.take(0ms).empty());
  q.push({K::velocity, 1.5});
  q.push({K::pause, 0.0});
  auto got = q.take(0ms);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].kind, K::velocity);
  EXPECT_EQ(got[0].value, 1.5);
  EXPECT_EQ(got[1].kind, K::pause);
  std::thread pusher([&] {
    std::this_thread::sleep_for(20ms);
    q.push({K::reset, 0.0});
  });
  const auto t0 = std::chrono::steady_clock::now();
  got = q.take(10s);
  pusher.join();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].kind, K::reset);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);  // woken, not timed out
}

// ---------------------------------------------------------------------------------------------
// The engine thread.

ViewEngine::Options paused() {
  ViewEngine::Options o;
  o.start_running = false;
  return o;
}

void post_and_wait(ViewEngine& e, const ViewCommand& c) {
  e.post(c);
  ASSERT_TRUE(e.wait_until_stopped(kTimeout)) << "engine did not stop";
}

TEST(ViewEngine, StartsFromTheSceneAndPublishesIt) {
  const Settings s = testing::view_test_settings();
  Simulation reference(s);
  ViewEngine e(s, paused());
  e.start();
  ASSERT_TRUE(e.wait_until_stopped(kTimeout));
  const app::EngineStatus st = e.status();
  EXPECT_EQ(st.state_hash, reference.state_hash());  // the viewer starts where `run` starts
  EXPECT_EQ(st.start_hash, reference.state_hash());
  EXPECT_EQ(st.particles, 100u);
  EXPECT_FALSE(st.stepping);
  auto snap = e.snapshots().latest();
  ASSERT_NE(snap, nullptr);
  EXPECT_EQ(snap->particles(), 100u);
  EXPECT_EQ(snap->step, 0);
}

TEST(ViewEngine, SingleStepsAndPauseStopSimulatedTime) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  post_and_wait(e, {K::step, 3.0});
  EXPECT_EQ(e.status().steps, 3);
  EXPECT_EQ(e.snapshots().latest()->step, 3);
  EXPECT_NEAR(e.status().time, 3 * s.time.dt, 1e-15);

  e.post({K::run, 0.0});
  // Running: simulated time moves.
  const auto t0 = std::chrono::steady_clock::now();
  while (e.status().steps < 50 && std::chrono::steady_clock::now() - t0 < kTimeout)
    std::this_thread::sleep_for(1ms);
  EXPECT_GE(e.status().steps, 50);
  post_and_wait(e, {K::pause, 0.0});
  const app::EngineStatus a = e.status();
  std::this_thread::sleep_for(100ms);
  const app::EngineStatus b = e.status();
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.state_hash, b.state_hash);
  EXPECT_EQ(e.snapshots().latest()->step, a.steps);  // the display shows where it stopped
}

TEST(ViewEngine, VelocityChangesTheJetWithinOneGasStep) {
  const Settings s = testing::view_test_settings();
  ASSERT_EQ(s.coupling.particle_steps_per_gas_step, 2);
  ViewEngine e(s, paused());
  e.start();
  post_and_wait(e, {K::step, 2.0});  // one gas step at the scene's 2.0 m/s
  const double jet0 = e.status().inlet_jet_velocity;
  ASSERT_GT(jet0, 2.0);  // a jet: faster than the superficial velocity
  post_and_wait(e, {K::velocity, 3.0});
  EXPECT_EQ(e.status().superficial_velocity, 3.0);
  EXPECT_NEAR(e.status().jet_velocity, 3.0 * s.domain.width / s.inlet.jet_width, 1e-12);
  post_and_wait(e, {K::step, 1.0});  // between gas steps: the gas has not stepped yet
  EXPECT_EQ(e.status().inlet_jet_velocity, jet0);
  post_and_wait(e, {K::step, 1.0});  // the next gas step uses the new velocity
  EXPECT_NEAR(e.status().inlet_jet_velocity, jet0 * 3.0 / 2.0, 1e-9 * jet0);
}

TEST(ViewEngine, ResetRestoresThePackedStateExactly) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  const std::uint64_t start = e.status().start_hash;
  post_and_wait(e, {K::velocity, 3.5});
  post_and_wait(e, {K::step, 40.0});
  const std::uint64_t after40 = e.status().state_hash;
  EXPECT_NE(after40, start);
  post_and_wait(e, {K::step, 20.0});
  post_and_wait(e, {K::reset, 0.0});
  const app::EngineStatus r = e.status();
  EXPECT_EQ(r.steps, 0);
  EXPECT_EQ(r.time, 0.0);
  EXPECT_EQ(r.generation, 1u);
  // The packed bed at the velocity the teacher set (the scene's is 2.0 m/s).
  EXPECT_EQ(r.superficial_velocity, 3.5);
  EXPECT_EQ(e.snapshots().latest()->step, 0);
  // The same commands from the reset state give the same bits: a reset bed runs as the first.
  post_and_wait(e, {K::velocity, 3.5});
  post_and_wait(e, {K::step, 40.0});
  EXPECT_EQ(e.status().state_hash, after40);
  // At the scene's velocity, Reset is the start bit for bit.
  post_and_wait(e, {K::velocity, 2.0});
  post_and_wait(e, {K::reset, 0.0});
  EXPECT_EQ(e.status().state_hash, start);
  EXPECT_EQ(e.status().superficial_velocity, 2.0);
}


// The outlines' toggle: with it the snapshots carry the fine void fraction (holding the spheres'
// volume) and the outlines; the physics is the same bits; without it the fields are empty again.
TEST(ViewEngine, BubbleToggleFillsTheSnapshotsFieldsAndLeavesThePhysics) {
  const Settings s = testing::view_test_settings();
  ViewEngine plain(s, paused()), with(s, paused());
  plain.start();
  with.start();
  post_and_wait(plain, {K::step, 30.0});
  post_and_wait(with, {K::bubbles, 1.0});
  post_and_wait(with, {K::step, 30.0});
  EXPECT_EQ(with.status().state_hash, plain.status().state_hash);
  EXPECT_TRUE(plain.snapshots().latest()->void_fraction.empty());
  auto snap = with.snapshots().latest();
  ASSERT_EQ(snap->void_nx, 20);  // 0.04 m / 2 mm
  ASSERT_EQ(snap->void_ny, 60);  // 0.12 m / 2 mm
  ASSERT_EQ(snap->void_fraction.size(), 1200u);
  double solid = 0.0;
  for (float e : snap->void_fraction)
    solid += (1.0 - e) * snap->void_dx * snap->void_dy * snap->thickness;
  double spheres = 0.0;
  for (std::size_t i = 0; i < snap->particles(); ++i)
    spheres += 4.0 / 3.0 * M_PI * std::pow(snap->radius[i], 3);
  EXPECT_NEAR(solid, spheres, 1e-3 * spheres);
  EXPECT_EQ(snap->bubble_edges.size() % 4, 0u);
  post_and_wait(with, {K::bubbles, 0.0});
  post_and_wait(with, {K::step, 2.0});
  post_and_wait(with, {K::step, 2.0});  // both pool buffers republished
  EXPECT_TRUE(with.snapshots().latest()->void_fraction.empty());
  EXPECT_TRUE(with.snapshots().latest()->bubble_edges.empty());
}

TEST(ViewEngine, IdealCaseKeepsTheStateAndChangesTheContactLaw) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  post_and_wait(e, {K::step, 200.0});
  const std::uint64_t before = e.status().state_hash;
  post_and_wait(e, {K::ideal, 1.0});
  EXPECT_TRUE(e.status().ideal);
  EXPECT_EQ(e.status().state_hash, before);  // the whole state carried across bit for bit
  post_and_wait(e, {K::step, 100.0});
  const std::uint64_t ideal_run = e.status().state_hash;
  // The same 100 steps with the scene's damping and friction end elsewhere.
  app::ViewModel plain(s);
  for (int k = 0; k < 300; ++k) plain.sim().step();
  EXPECT_NE(plain.sim().state_hash(), ideal_run);
  // Reset keeps the ideal choice and returns to the start.
  post_and_wait(e, {K::reset, 0.0});
  EXPECT_TRUE(e.status().ideal);
  EXPECT_EQ(e.status().state_hash, e.status().start_hash);
  // And the ideal model can be left again.
  post_and_wait(e, {K::ideal, 0.0});
  EXPECT_FALSE(e.status().ideal);
  post_and_wait(e, {K::step, 300.0});
  EXPECT_EQ(e.status().state_hash, plain.sim().state_hash());
}

TEST(ViewEngine, NegativeVelocityIsTakenAsZero) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  // The panel clamps; a negative velocity from elsewhere is taken as 0.
  post_and_wait(e, {K::velocity, -1.0});
  EXPECT_EQ(e.status().superficial_velocity, 0.0);
  EXPECT_TRUE(e.status().error.empty());
}

TEST(ViewEngine, RunUntilStopsAtTheNearestStep) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  post_and_wait(e, {K::run_until, 0.0012});
  EXPECT_EQ(e.status().steps, std::llround(0.0012 / s.time.dt));
  EXPECT_EQ(e.snapshots().latest()->step, e.status().steps);
  // The plots: one sample per output interval (1 ms) so far.
  const auto samples = e.take_samples();
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_NEAR(samples[0].t, 0.001, 0.5 * s.time.dt);
  EXPECT_GT(samples[0].dp, 0.0);
}

// The engine/viewer pair: the engine runs while a reader thread takes snapshots as a window would
// and the "panel" sends every kind of command. Every snapshot is whole; the engine never waits.
TEST(ViewEngine, EngineAndViewerThreadsTogether) {
  const Settings s = testing::view_test_settings();
  ViewEngine::Options o;
  o.publish_interval = 0.0005;
  ViewEngine e(s, o);
  e.start();
  std::atomic<bool> stop{false};
  std::atomic<int> frames{0}, bad{0};
  std::thread viewer([&] {
    std::uint64_t last_seq = 0;
    while (!stop.load()) {
      std::uint64_t seq = 0;
      auto snap = e.snapshots().latest(&seq);
      const app::EngineStatus st = e.status();
      (void)e.take_samples();
      if (!snap || seq == last_seq) {
        std::this_thread::sleep_for(200us);
        continue;
      }
      last_seq = seq;
      // "Drawing": read every array.
      double sum = 0.0;
      for (std::size_t i = 0; i < snap->particles(); ++i)
        sum += snap->x[i] + snap->vy[i] + snap->fx[i];
      bad += (snap->particles() != 100 || snap->gas_ux.size() != 48 || !std::isfinite(sum) ||
              st.particles != 100)
                 ? 1
                 : 0;
      ++frames;
    }
  });
  const ViewCommand script[] = {{K::velocity, 2.5}, {K::pause, 0}, {K::step, 5},
                                {K::run, 0},        {K::ideal, 1}, {K::velocity, 1.0},
                                {K::reset, 0},      {K::ideal, 0}, {K::run, 0}};
  for (const ViewCommand& c : script) {
    e.post(c);
    std::this_thread::sleep_for(30ms);
  }
  post_and_wait(e, {K::pause, 0.0});
  stop.store(true);
  viewer.join();
  EXPECT_GT(frames.load(), 3);
  EXPECT_EQ(bad.load(), 0);
  EXPECT_TRUE(e.status().error.empty()) << e.status().error;
  EXPECT_EQ(e.status().generation, 1u);
}

// Waits until `done(status)` holds (the engine running on its own), up to kTimeout.
template <class F>
bool wait_for(const ViewEngine& e, F done) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!done(e.status())) {
    if (std::chrono::steady_clock::now() - t0 > kTimeout) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

// After reset number `generation`: the bed steps again, past 20 steps, with no error.
bool runs_again_after_reset(const ViewEngine& e, std::uint64_t generation) {
  return wait_for(e, [generation](const app::EngineStatus& st) {
    return st.generation == generation && st.steps > 20 && st.stepping && st.error.empty();
  });
}

// A failure says what to do in the viewer (not "reduce the time step"), and Reset after it does
// what Reset does during a run: the bed runs again from the start (the run switch is untouched).
TEST(ViewEngine, FailureSaysWhatToDoAndResetResumesAsDuringARun) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, ViewEngine::Options{});  // running
  e.start();
  ASSERT_TRUE(wait_for(e, [](const app::EngineStatus& st) { return st.steps > 20; }));
  // Reset during a run: it goes on running.
  e.post({K::reset, 0.0});
  ASSERT_TRUE(wait_for(e, [](const app::EngineStatus& st) {
    return st.generation == 1 && st.steps > 20 && st.stepping;
  }));
  // A jet of 2000 m/s: the gas fails on its CFL number at its first step.
  e.post({K::velocity, 500.0});
  ASSERT_TRUE(wait_for(e, [](const app::EngineStatus& st) { return !st.error.empty(); }));
  const app::EngineStatus failed = e.status();
  EXPECT_FALSE(failed.stepping);
  EXPECT_TRUE(failed.running);  // the switch as the user left it
  EXPECT_NE(failed.error.find("Press Reset"), std::string::npos) << failed.error;
  EXPECT_NE(failed.error.find("keep the gas below 500.00 m/s"), std::string::npos) << failed.error;
  EXPECT_NE(failed.error.find("CFL"), std::string::npos) << failed.error;
  EXPECT_EQ(failed.error.find("reduce the time step"), std::string::npos) << failed.error;
  // Reset after the failure: the same as during a run.
  e.post({K::reset, 0.0});
  ASSERT_TRUE(runs_again_after_reset(e, 2)) << e.status().error;
  EXPECT_EQ(e.status().superficial_velocity, 2.0);
}

// A scene that fails at its start (a velocity its gas step cannot follow) is not a dead end: the
// message says to lower the gas first, and Reset then starts the packed bed at the lower one.
TEST(ViewEngine, AFailedStartIsRecoveredByResetAtALowerVelocity) {
  Settings s = testing::view_test_settings();
  s.inlet.superficial_velocity = 500.0;
  ViewEngine e(s, ViewEngine::Options{});  // running
  e.start();
  ASSERT_TRUE(wait_for(e, [](const app::EngineStatus& st) { return !st.error.empty(); }));
  const std::string failed = e.status().error;
  EXPECT_NE(failed.find("Lower the gas, then press Reset"), std::string::npos) << failed;
  EXPECT_NE(failed.find("keep the gas below 500.00 m/s"), std::string::npos) << failed;
  // Reset alone starts again at 500 m/s, and fails again: the teacher has not lowered it.
  e.post({K::reset, 0.0});
  ASSERT_TRUE(wait_for(e, [](const app::EngineStatus& st) {
    return st.generation == 1 && !st.error.empty();
  }));
  EXPECT_EQ(e.status().superficial_velocity, 500.0);
  e.post({K::velocity, 2.0});
  e.post({K::reset, 0.0});
  ASSERT_TRUE(runs_again_after_reset(e, 2)) << e.status().error;
  EXPECT_EQ(e.status().superficial_velocity, 2.0);
}

// The fault: at the slider's top the teaching bed was blown against the top screen (overlap
// 12.8 %, dp 8,200 Pa for seconds) and nothing said so. A bed 7 cm high under a screen: at 5 m/s
// its spheres are held against the screen, said after a second of it; at 2 m/s never; Reset
// clears it.
TEST(ViewSession, ABedHeldAgainstTheTopScreenIsSaidAfterASecond) {
#if defined(__SANITIZE_THREAD__)
  // One thread stepping a session for two simulated seconds: 55 s under the thread sanitizer,
  // which this binary runs for the engine's threads; the Release and address-sanitizer runs
  // cover it.
  GTEST_SKIP() << "single-threaded; not run under the thread sanitizer";
#endif
  Settings s = testing::view_test_settings();
  s.domain.top_wall = true;
  s.domain.height = 0.07;
  const auto first_held = [](app::ViewSession& v, double until) {
    while (v.sim().time() < until) {
      v.step();
      if (v.held_at_top() > 0) return v.sim().time();
    }
    return -1.0;
  };
  app::ViewSession calm(s);
  EXPECT_LT(first_held(calm, 1.2), 0.0);
  s.inlet.superficial_velocity = 5.0;
  app::ViewSession blown(s);
  const double t = first_held(blown, 2.0);
  EXPECT_GE(t, app::ViewSession::kHeldAtTop);
  EXPECT_LT(t, 2.0);
  blown.apply({K::reset, 0.0});
  EXPECT_EQ(blown.held_at_top(), 0);
}

// Runs shorter than the speed's quarter second (a script's `at T` lines) still give a speed.
TEST(ViewEngine, ShortRunsAreTimedForTheSpeed) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  EXPECT_EQ(e.status().sim_s_per_wall_s, 0.0);
  post_and_wait(e, {K::run_until, 0.05});  // tens of milliseconds, not a quarter second
  EXPECT_GT(e.status().sim_s_per_wall_s, 0.0);
  EXPECT_GT(e.status().steps_per_s, 0.0);
}

// The live Fig. 6 through the engine's commands: three held velocities, three points on the
// increasing branch; a lower one starts the decreasing branch; Reset clears it.
TEST(ViewEngine, LiveCurveTakesOnePointPerHeldVelocity) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  post_and_wait(e, {K::settle, 0.005});
  post_and_wait(e, {K::average, 0.01});
  EXPECT_EQ(e.status().curve.settle, 0.005);
  EXPECT_EQ(e.status().curve.window, 0.01);
  post_and_wait(e, {K::run_until, 0.02});  // the scene's 2 m/s
  for (double u : {2.5, 3.0}) {
    post_and_wait(e, {K::velocity, u});
    post_and_wait(e, {K::run_until, e.status().time + 0.02});
  }
  app::CurveState c = e.status().curve;
  ASSERT_EQ(c.branches.size(), 1u);
  EXPECT_TRUE(c.branches[0].increasing);
  ASSERT_EQ(c.branches[0].points.size(), 3u);
  EXPECT_EQ(c.branches[0].points[0].u, 2.0);
  EXPECT_EQ(c.branches[0].points[2].u, 3.0);
  EXPECT_EQ(c.branches[0].points[0].samples, 10);  // 10 ms at one sample per ms
  EXPECT_GT(c.branches[0].points[0].dp_mean, 0.0);
  EXPECT_GT(c.weight_per_area, 0.0);
  post_and_wait(e, {K::velocity, 2.2});
  post_and_wait(e, {K::run_until, e.status().time + 0.02});
  c = e.status().curve;
  ASSERT_EQ(c.branches.size(), 2u);
  EXPECT_FALSE(c.branches[1].increasing);
  ASSERT_EQ(c.branches[1].points.size(), 2u);  // the turning point and 2.2 m/s
  EXPECT_EQ(c.branches[1].points[1].u, 2.2);
  post_and_wait(e, {K::reset, 0.0});
  c = e.status().curve;
  ASSERT_EQ(c.branches.size(), 1u);
  EXPECT_TRUE(c.branches[0].points.empty());
}

// A stiffness the scene's step can take: the state carries over; one it cannot: refused in one
// line, the bed as it was.
TEST(ViewEngine, StiffnessKeepsTheStateAndRefusesAStepTooLong) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  post_and_wait(e, {K::step, 50.0});
  const std::uint64_t before = e.status().state_hash;
  post_and_wait(e, {K::stiffness, 800.0});
  EXPECT_EQ(e.status().stiffness, 800.0);
  EXPECT_EQ(e.status().state_hash, before);
  EXPECT_TRUE(e.status().refusal.empty());
  post_and_wait(e, {K::stiffness, 5e8});
  EXPECT_NE(e.status().refusal.find("stiffness 5e+08 N/m is refused"), std::string::npos)
      << e.status().refusal;
  EXPECT_EQ(e.status().stiffness, 800.0);
  EXPECT_TRUE(e.status().error.empty());
  post_and_wait(e, {K::step, 5.0});
  EXPECT_EQ(e.status().steps, 55);
  // The damping follows sqrt(kappa): the restitution of the scene.
  const Settings soft = app::with_contact(s, false, 800.0);
  EXPECT_NEAR(soft.contact.damping, s.contact.damping * std::sqrt(800.0 / s.contact.stiffness),
              1e-15);
}

// Other spheres, by hand: the mass ratio r = (rho / rho_0) (d / d_0)^3 = 2 x (1/2)^3 = 1/4, so
// the linear law's step and damping both scale by sqrt(r) = 1/2; Hertz's step by
// r^(2/5) (d / d_0)^(-1/5) = 0.25^0.4 x 2^0.2 = 0.65975; the gas step (2 particle steps) stays
// the scene's at most: 4 and 3 particle steps in it; the monolayer stays one sphere thick; a
// lattice start's fill height scales with the area, 1/4. Heavier spheres (r = 16): the step
// would be 4 dt, more than the gas step; it is the gas step, one particle step to it.
TEST(ViewSession, NewParticlesTakeTheScenesStepRule) {
  Settings s = testing::view_test_settings();
  s.particles.packing_scene = "elsewhere.toml";
  const Settings p = app::with_particles(s, 0.002, 5400.0);
  EXPECT_EQ(p.particles.count, s.particles.count);
  EXPECT_EQ(p.particles.diameter, 0.002);
  EXPECT_EQ(p.particles.density, 5400.0);
  EXPECT_NEAR(p.time.dt, 0.5 * s.time.dt, 1e-20);
  EXPECT_NEAR(p.contact.damping, 0.5 * s.contact.damping, 1e-15);
  EXPECT_EQ(s.coupling.particle_steps_per_gas_step, 2);
  EXPECT_EQ(p.coupling.particle_steps_per_gas_step, 4);
  EXPECT_EQ(p.contact.stiffness, s.contact.stiffness);
  EXPECT_EQ(p.domain.thickness, 0.002);
  EXPECT_NEAR(p.particles.fill_height, 0.25 * s.particles.fill_height, 1e-15);
  EXPECT_TRUE(p.particles.packing_scene.empty());  // that scene packs the old spheres
  Settings hm = s;
  hm.contact.law = ContactLaw::HertzMindlin;
  const Settings q = app::with_particles(hm, 0.002, 5400.0);
  EXPECT_NEAR(q.time.dt, 0.65975 * s.time.dt, 1e-5 * s.time.dt);
  EXPECT_EQ(q.contact.damping, s.contact.damping);  // Hertz-Mindlin's is the restitution's
  EXPECT_EQ(q.coupling.particle_steps_per_gas_step, 3);
  const Settings heavy = app::with_particles(s, 0.004, 16.0 * 2700.0);
  EXPECT_EQ(heavy.time.dt, 2.0 * s.time.dt);
  EXPECT_EQ(heavy.coupling.particle_steps_per_gas_step, 1);
  // Refused: no size, no density, spheres wider than a thick slab's walls are apart.
  EXPECT_THROW(app::with_particles(s, 0.0, 2700.0), InputError);
  EXPECT_THROW(app::with_particles(s, 0.003, -1.0), InputError);
  Settings slab = s;
  slab.domain.thickness = 0.012;
  EXPECT_EQ(app::with_particles(slab, 0.003, 2700.0).domain.thickness, 0.012);  // kept
  try {
    app::with_particles(slab, 0.02, 2700.0);
    ADD_FAILURE() << "a 20 mm sphere between walls 12 mm apart was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("spheres of 20 mm"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("do not fit"), std::string::npos) << e.what();
  }
}

// The engine's particles command: the count and the held velocity kept, the time back to 0, the
// new step; a refused size leaves the bed as it was; 0 and 0 give the scene's spheres back.
TEST(ViewEngine, NewParticlesKeepTheCountAndTheVelocity) {
  const Settings s = testing::view_test_settings();
  ViewEngine e(s, paused());
  e.start();
  post_and_wait(e, {K::velocity, 1.5});
  post_and_wait(e, {K::step, 20.0});
  const std::uint64_t generation = e.status().generation;
  post_and_wait(e, {K::particles, 0.003, 2500.0});
  app::EngineStatus st = e.status();
  EXPECT_TRUE(st.refusal.empty()) << st.refusal;
  EXPECT_TRUE(st.error.empty()) << st.error;
  EXPECT_EQ(st.particles, 100u);
  EXPECT_EQ(st.particle_diameter, 0.003);
  EXPECT_EQ(st.particle_density, 2500.0);
  EXPECT_EQ(st.steps, 0);
  EXPECT_EQ(st.superficial_velocity, 1.5);
  EXPECT_GT(st.generation, generation);  // the plots start again
  EXPECT_EQ(st.particles_changes, 1u);
  EXPECT_NEAR(st.dt, s.time.dt * std::sqrt(2500.0 / 2700.0 * 0.421875), 1e-18);  // 2 fit
  EXPECT_TRUE(st.busy.empty());
  auto snap = e.snapshots().latest();
  ASSERT_NE(snap, nullptr);
  EXPECT_DOUBLE_EQ(snap->radius.at(0), 0.0015);
  post_and_wait(e, {K::step, 10.0});
  EXPECT_EQ(e.status().steps, 10);
  post_and_wait(e, {K::particles, 0.02, 2500.0});
  st = e.status();
  EXPECT_NE(st.refusal.find("spheres of 20 mm and 2500 kg/m^3: particles.count: only 93 fit"),
            std::string::npos)
      << st.refusal;
  EXPECT_EQ(st.particle_diameter, 0.003);
  EXPECT_EQ(st.steps, 10);
  post_and_wait(e, {K::particles, 0.0, 0.0});
  st = e.status();
  EXPECT_EQ(st.particle_diameter, s.particles.diameter);
  EXPECT_EQ(st.dt, s.time.dt);
  EXPECT_EQ(st.particles_changes, 2u);
}

}  // namespace
}  // namespace fluidbed
