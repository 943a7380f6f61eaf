// Determinism: the same scene and seed give the same state bits; a saved and reloaded state
// continues exactly as the uninterrupted run.
#include <gtest/gtest.h>

#include <sstream>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "sim/simulation.hpp"

using namespace fluidbed;

namespace {

Settings determinism_bed() {
  Settings s;
  s.scene.kind = SceneKind::Packing;
  s.domain.width = 0.06;
  s.domain.height = 0.2;
  s.particles.count = 300;
  s.particles.seed = 7;
  return s;
}

// The same spheres in the paper's column with gas at u (m/s), filled to `fill` (m).
Settings gas_bed(double fill, double u) {
  Settings s = determinism_bed();
  s.domain.width = 0.15;
  s.domain.height = 0.9;
  s.particles.fill_height = fill;
  s.gas.enabled = true;
  s.inlet.superficial_velocity = u;
  return s;
}

std::uint64_t run_steps(Simulation& sim, int n) {
  for (int k = 0; k < n; ++k) sim.step();
  return sim.state_hash();
}

}  // namespace

TEST(Determinism, SameSceneSameHash) {
  Simulation a(determinism_bed()), b(determinism_bed());
  const auto ha = run_steps(a, 8000), hb = run_steps(b, 8000);
  EXPECT_EQ(ha, hb);
  EXPECT_GT(a.dem().diagnostics().pair_contacts, 50);  // the particles have landed and touch
  Settings other = determinism_bed();
  other.particles.seed = 8;
  Simulation c(other);
  EXPECT_NE(run_steps(c, 8000), ha);
}

TEST(Determinism, SaveLoadContinueIsBitExact) {
  for (const char* integrator : {"newmark", "velocity_verlet", "symplectic_euler"}) {
    Settings s = determinism_bed();
    s.time.integrator = parse_option<Integrator>("time.integrator", integrator);
    Simulation straight(s);
    const auto expected = run_steps(straight, 8000);

    Simulation first(s);
    run_steps(first, 5000);
    const auto dir = fluidbed::testing::temp_dir("saveload");
    const std::string path = (dir / "mid.state").string();
    first.save_state(path);

    Simulation resumed(s);
    resumed.load_state(path);
    EXPECT_EQ(resumed.state_hash(), first.state_hash());
    EXPECT_EQ(run_steps(resumed, 3000), expected) << integrator;
  }
}

TEST(Determinism, CoupledSaveLoadContinueIsBitExact) {
  // Particles, gas and coupling together: a jetted bed of 300 spheres, gas every other step;
  // as placed, and renumbered by cell every 500 steps (the file then holds the particles' order,
  // and the resumed run renumbers again: dem/renumber.cpp).
  for (const int renumber : {0, 500}) {
    SCOPED_TRACE(renumber);
    Settings s = gas_bed(0.2, 2.0);
    s.inlet.kind = InletKind::Jet;
    s.coupling.particle_steps_per_gas_step = 2;
    s.contact.renumber_steps = renumber;
    Simulation straight(s);
    const auto expected = run_steps(straight, 3001);
    Simulation first(s);
    run_steps(first, 2001);  // mid-way through a gas sub-step cycle
    EXPECT_EQ(first.dem().renumbered(), renumber > 0);
    const auto dir = fluidbed::testing::temp_dir("saveload-gas");
    const std::string path = (dir / "mid.state").string();
    first.save_state(path);
    Simulation resumed(s);
    resumed.load_state(path);
    EXPECT_EQ(resumed.dem().ids(), first.dem().ids());
    EXPECT_EQ(resumed.state_hash(), first.state_hash());
    EXPECT_EQ(run_steps(resumed, 1000), expected);
  }
}

TEST(Determinism, SameBitsForOneAndTwoThreads) {
  // The particle step gathers pair forces in a fixed order, and sums over particles (energy,
  // porosity, drag per cell) are taken block by block and added in block order: the thread count
  // changes the speed, not a bit of the result. 600 particles: 10 blocks, split unevenly by work;
  // as placed, and renumbered by cell every 500 steps (the same order on both).
  for (const int renumber : {0, 500}) {
    SCOPED_TRACE(renumber);
    Settings s = gas_bed(0.25, 2.5);
    s.particles.count = 600;
    s.contact.renumber_steps = renumber;
    s.threads = 1;
    Simulation one(s);
    s.threads = 2;
    Simulation two(s);
    EXPECT_EQ(two.dem().threads(), 2);
    EXPECT_EQ(run_steps(one, 1500), run_steps(two, 1500));
    EXPECT_EQ(one.dem().ids(), two.dem().ids());
    EXPECT_EQ(one.dem().renumbered(), renumber > 0);
    EXPECT_GT(one.dem().diagnostics().pair_contacts, 20);  // contacts and gas both exercised
  }
}

TEST(Determinism, StateFileRejectsGarbage) {
  const auto dir = fluidbed::testing::temp_dir("garbage");
  fluidbed::testing::write_file(dir / "bad.state", "not a state");
  Simulation sim(determinism_bed());
  EXPECT_THROW(sim.load_state((dir / "bad.state").string()), InputError);
  EXPECT_THROW(sim.load_state((dir / "missing.state").string()), InputError);
}

TEST(Determinism, StateWithoutLidStartsASceneWithOne) {
  // A bed packed open at the top starts a scene with a top wall (the teaching scene's screen):
  // the top wall's history starts empty and the particles continue exactly as in the open bed
  // while none of them reaches the lid.
  Settings s = determinism_bed();
  s.domain.height = 0.3;
  Simulation packed(s);
  run_steps(packed, 3000);
  const auto dir = fluidbed::testing::temp_dir("lid");
  const std::string path = (dir / "open.state").string();
  packed.save_state(path);

  Settings open = s, lid = s;
  for (Settings* t : {&open, &lid}) {
    t->particles.placement = Placement::State;
    t->particles.state_file = path;
  }
  lid.domain.top_wall = true;
  Simulation a(open), b(lid);
  EXPECT_EQ(b.dem().walls().size(), a.dem().walls().size() + 1);
  EXPECT_EQ(b.dem().state().walls.walls, 4);
  run_steps(a, 2000);
  run_steps(b, 2000);
  for (std::size_t i = 0; i < a.particle_count(); ++i) {
    ASSERT_EQ(a.dem().particles().x[i], b.dem().particles().x[i]) << i;
    ASSERT_EQ(a.dem().particles().y[i], b.dem().particles().y[i]) << i;
  }
}
