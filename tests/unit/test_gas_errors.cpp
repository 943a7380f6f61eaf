// The gas solver refuses impossible parameters (InputError, naming the field) and reports a run
// that blows up (SimulationFailure, naming the cell and the time).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "cfd/gas_solver.hpp"
#include "core/errors.hpp"

using namespace fluidbed;

namespace {

std::string input_error(const GasGrid& g, const std::function<void(GasParams&)>& change) {
  GasParams p;
  change(p);
  try {
    GasSolver gas(g, p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string failure_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const SimulationFailure& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(GasErrors, ImpossibleParametersNameTheField) {
  const GasGrid g;
  EXPECT_NE(input_error(g, [](GasParams& p) { p.viscosity = -1e-5; }).find("gas.viscosity"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.density = 0.0; }).find("gas.density"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.jet_width = 0.2; }).find("gas.jet_width"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.jet_width = 0.0; }).find("gas.jet_width"),
            std::string::npos);
  // An unknown inlet cannot reach the gas solver: the scene's name is an enum from the loader
  // on (test_scene.cpp: inlet.kind = "nozzle" is refused there).
  EXPECT_NE(input_error(g, [](GasParams& p) { p.superficial_velocity = -1.0; })
                .find("gas.superficial_velocity"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.tolerance = 0.0; }).find("gas.tolerance"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.max_iterations = 0; }).find("gas.max_iterations"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.velocity_relaxation = 1.5; })
                .find("gas.velocity_relaxation"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.pressure_relaxation = 0.0; })
                .find("gas.pressure_relaxation"),
            std::string::npos);
  EXPECT_NE(input_error(g, [](GasParams& p) { p.gravity = NAN; }).find("gas.gravity"),
            std::string::npos);
  // A jet wider than the bed is fine when there is no jet.
  EXPECT_EQ(input_error(g,
                        [](GasParams& p) {
                          p.inlet = InletKind::Uniform;
                          p.jet_width = 1.0;
                        }),
            "");
  GasGrid one = g;
  one.nx = 1;
  EXPECT_NE(input_error(one, [](GasParams&) {}).find("gas grid"), std::string::npos);
}

TEST(GasErrors, WrongArraySizesAndTimeStepAreInputErrors) {
  const GasGrid g;
  GasSolver gas(g, GasParams{});
  const std::vector<double> ok(g.cells(), 1.0), zero(g.cells(), 0.0), short_(10, 1.0);
  EXPECT_THROW(gas.step(1e-5, short_, zero, zero), InputError);
  EXPECT_THROW(gas.step(1e-5, ok, short_, zero), InputError);
  EXPECT_THROW(gas.step(0.0, ok, zero, zero), InputError);
  EXPECT_THROW(gas.set_porosity(short_), InputError);
  EXPECT_THROW(gas.set_porosity(zero), InputError);  // porosity 0
  GasState s = gas.state();
  s.u.pop_back();
  EXPECT_THROW(gas.set_state(s), InputError);
}

TEST(GasErrors, CflAboveOneFailsNamingCflCellAndTime) {
  // 20 m/s through the bottom with dt = 1 ms: CFL = 20 * 1e-3 / 0.01 = 2.
  const GasGrid g;
  GasParams p;
  p.inlet = InletKind::Uniform;
  p.superficial_velocity = 20.0;
  GasSolver gas(g, p);
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  const std::string what = failure_of([&] { gas.step(1e-3, eps, zero, zero); });
  EXPECT_NE(what.find("CFL"), std::string::npos) << what;
  EXPECT_NE(what.find("cell ("), std::string::npos) << what;
  EXPECT_NE(what.find("t = "), std::string::npos) << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;  // one line
}

TEST(GasErrors, NonFiniteInputFailsNamingTheCell) {
  const GasGrid g;
  GasSolver gas(g, GasParams{});
  std::vector<double> eps(g.cells(), 1.0), fx(g.cells(), 0.0), fy(g.cells(), 0.0);
  fy[g.index(4, 9)] = NAN;
  const std::string what = failure_of([&] { gas.step(1.5e-5, eps, fx, fy); });
  EXPECT_NE(what.find("cell (4, 9)"), std::string::npos) << what;
  fy[g.index(4, 9)] = 0.0;
  eps[g.index(2, 3)] = 1.5;
  const std::string bad_eps = failure_of([&] { gas.step(1.5e-5, eps, fx, fy); });
  EXPECT_NE(bad_eps.find("porosity"), std::string::npos) << bad_eps;
  EXPECT_NE(bad_eps.find("cell (2, 3)"), std::string::npos) << bad_eps;
}

TEST(GasErrors, NanInTheFieldIsCaughtAfterTheIteration) {
  // A NaN inside the field (here planted through the state) is reported with its face, not
  // carried on into the drag.
  const GasGrid g;
  GasSolver gas(g, GasParams{});
  GasState s = gas.state();
  s.v[g.nx * 20 + 3] = NAN;
  gas.set_state(s);
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  const std::string what = failure_of([&] { gas.step(1.5e-5, eps, zero, zero); });
  EXPECT_NE(what.find("not finite"), std::string::npos) << what;
  EXPECT_NE(what.find("cell ("), std::string::npos) << what;
}

TEST(GasErrors, SimpleThatStopsShortReportsOrFails) {
  const GasGrid g;
  const std::vector<double> eps(g.cells(), 1.0), zero(g.cells(), 0.0);
  {
    // The impulsive start of the jet in one SIMPLE iteration: the residual is far above
    // 1000 x tolerance, so the step fails and says why.
    GasParams p;
    p.max_iterations = 1;
    p.tolerance = 1e-12;
    GasSolver gas(g, p);
    const std::string what = failure_of([&] { gas.step(1.5e-5, eps, zero, zero); });
    EXPECT_NE(what.find("SIMPLE did not converge"), std::string::npos) << what;
    EXPECT_NE(what.find("cell ("), std::string::npos) << what;
  }
  {
    // Steady jet flow, then one iteration per step: the residual left is small but above the
    // tolerance (and below 1000 x): reported, not thrown.
    GasParams p;
    GasSolver gas(g, p);
    for (int k = 0; k < 200; ++k) gas.step(1.5e-5, eps, zero, zero);
    GasState s = gas.state();
    p.max_iterations = 1;
    GasSolver short_(g, p);
    short_.set_state(s);
    GasStepReport rep;
    EXPECT_NO_THROW(rep = short_.step(1.5e-5, eps, zero, zero));
    EXPECT_EQ(rep.simple_iterations, 1);
    EXPECT_GT(rep.mass_residual, p.tolerance);
    EXPECT_LT(rep.mass_residual, 1000.0 * p.tolerance);
    EXPECT_FALSE(rep.converged);
  }
}

TEST(GasErrors, StepThatOutrunsItsCflIsTakenAgainAsSubsteps) {
  // A column whose rows 10 to 19 hold porosity 0.5, fed with 4.5 m/s: two short steps (dt = 1e-4 s,
  // CFL 0.09) give the solver a history and a factorization, with 9 m/s in the packed rows. Then
  // the inlet goes to 9 m/s and a step of dt = 1 ms starts at CFL 9 x 1e-3 / 0.01 = 0.9, while the
  // packed rows loosen to 0.52: there the gas reaches about 17 m/s, CFL 1.7 at the end of the step.
  // It is taken again as ceil(1.7 / 0.8) = 3 sub-steps, the porosity moving a third of the way in
  // each: the same bits as three explicit steps of dt / 3 with those porosities.
  const GasGrid g;
  GasParams p;
  p.inlet = InletKind::Uniform;
  p.superficial_velocity = 4.5;
  const std::vector<double> zero(g.cells(), 0.0);
  std::vector<double> before(g.cells(), 1.0), after(g.cells(), 1.0);
  for (int j = 10; j < 20; ++j)
    for (int i = 0; i < g.nx; ++i) {
      before[g.index(i, j)] = 0.5;
      after[g.index(i, j)] = 0.52;
    }
  GasSolver split(g, p), thirds(g, p);
  for (GasSolver* gas : {&split, &thirds}) {
    gas->set_porosity(before);
    for (int k = 0; k < 2; ++k) EXPECT_EQ(gas->step(1e-4, before, zero, zero).substeps, 1);
    gas->set_superficial_velocity(9.0);
  }
  const GasStepReport rep = split.step(1e-3, after, zero, zero);
  EXPECT_EQ(rep.substeps, 3);
  EXPECT_GT(rep.max_cfl, 0.5);
  EXPECT_LE(rep.max_cfl, 1.0);
  int iterations = 0;
  for (int k = 1; k <= 3; ++k) {
    std::vector<double> level(g.cells());
    const double w = static_cast<double>(k) / 3;
    for (std::size_t c = 0; c < level.size(); ++c)
      level[c] = k == 3 ? after[c] : before[c] + w * (after[c] - before[c]);
    const GasStepReport r = thirds.step(1e-3 / 3, level, zero, zero);
    EXPECT_EQ(r.substeps, 1);
    iterations += r.simple_iterations;
  }
  EXPECT_EQ(rep.simple_iterations, iterations);
  EXPECT_EQ(split.state_hash(), thirds.state_hash());
  EXPECT_NEAR(split.time(), 2e-4 + 1e-3, 1e-15);

  // A step that already starts above CFL 1 (dt = 2 ms here) is the caller's error: refused.
  GasSolver too_long(g, p);
  too_long.set_porosity(before);
  too_long.set_superficial_velocity(9.0);
  const std::string what = failure_of([&] { too_long.step(2e-3, before, zero, zero); });
  EXPECT_NE(what.find("CFL"), std::string::npos) << what;
}
