// The run loop's own checks (engine/sim/run.cpp): a gas CFL number above the limit, a porosity out
// of range and a starting state that is not finite each end the run with one line of words.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "run/run_loop.hpp"
#include "sim/simulation.hpp"

using namespace fluidbed;

namespace {

// 60 spheres settling in still air in a small box with gas (6 x 15 cells of the paper's size).
Settings small_bed() {
  Settings s;
  s.domain.width = 0.06;
  s.domain.height = 0.3;
  s.particles.count = 60;
  s.particles.fill_height = 0.05;
  s.gas.enabled = true;
  s.gas.cells_x = 6;
  s.gas.cells_y = 15;
  s.inlet.kind = InletKind::Uniform;
  s.inlet.superficial_velocity = 1.0;
  return s;
}

std::string failure_of(Simulation& sim, const RunOptions& o) {
  try {
    run_simulation(sim, o);
  } catch (const SimulationFailure& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(RunChecks, GasCflAboveTheLimitFailsInWords) {
  Settings s = small_bed();
  RunOptions o;
  o.until = 0.003;
  {
    Simulation sim(s);
    EXPECT_EQ(failure_of(sim, o), "");  // 1 m/s, CFL 1.5e-3: fine at the default limit
  }
  // The same run with a limit below its CFL number (1 m/s x 1.5e-5 s / 0.01 m = 1.5e-3).
  o.cfl_limit = 1e-4;
  Simulation sim(s);
  const std::string what = failure_of(sim, o);
  EXPECT_NE(what.find("CFL"), std::string::npos) << what;
  EXPECT_NE(what.find("t = "), std::string::npos) << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
}

TEST(RunChecks, PorosityBelowTheFloorFailsNamingTheCell) {
  Settings s = small_bed();
  RunOptions o;
  o.until = 0.003;
  // The bed's lowest cells hold particles (porosity below 1): a floor of 0.999 is crossed.
  o.porosity_min = 0.999;
  Simulation sim(s);
  const std::string what = failure_of(sim, o);
  EXPECT_NE(what.find("porosity"), std::string::npos) << what;
  EXPECT_NE(what.find("gas cell ("), std::string::npos) << what;
  // The default floor (0.3) is far below any packing of spheres in the slab (0.395).
  Simulation ok(s);
  RunOptions d;
  d.until = 0.003;
  EXPECT_EQ(failure_of(ok, d), "");
}

TEST(RunChecks, NonFiniteStartIsRefusedBeforeTheFirstStep) {
  Settings s;
  s.scene.kind = SceneKind::Drop;
  s.particles.count = 1;
  s.particles.placement = Placement::Single;
  s.particles.vy = NAN;  // the scene loader refuses this; a program setting it directly is caught
  Simulation sim(s);
  RunOptions o;
  o.until = 0.001;
  const std::string what = failure_of(sim, o);
  EXPECT_NE(what.find("NaN"), std::string::npos) << what;
  EXPECT_EQ(sim.steps(), 0);
}
