// The gas coupled to the particles: Newton's third law, a hovering particle, the fixed-bed force
// balance and Ergun, minimum fluidization from the model, and the paper's jetted bed.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "../test_support.hpp"
#include "core/roots.hpp"
#include "coupling/drag.hpp"
#include "analysis/packing_metrics.hpp"
#include "scene/scene_loader.hpp"
#include "run/run_loop.hpp"
#include "sim/simulation.hpp"
#include "run/packed_bed.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

// The paper's bed; its packed start is prepared (made once and cached) whenever the placement
// is still "packed" after the overrides.
Settings paper_bed(std::vector<std::string> overrides = {}) {
  Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml", overrides);
  prepare_packed_bed(s);
  return s;
}

double total_fluid_force_y(const Simulation& sim) {
  const Particles& p = sim.dem().particles();
  return std::accumulate(p.ext_fy.begin(), p.ext_fy.end(), 0.0);
}
double total_drag_y(const Simulation& sim) {
  const auto& d = sim.coupler()->drag_y();
  return std::accumulate(d.begin(), d.end(), 0.0);
}

// The packed bed held fixed, uniform inflow at U, run until the gas is steady.
struct FixedBed {
  double dp, fluid_force, drag, weight_per_area, bed_height, solid_fraction, area, gas_weight;
};
FixedBed fixed_bed(double U) {
  Settings s = paper_bed({"particles.frozen=true", "inlet.kind=uniform"});
  s.inlet.superficial_velocity = U;
  Simulation sim(s);
  for (int k = 0; k < 2000; ++k) sim.step();  // 0.03 s: many gas response times (~1e-4 s)
  const Particles& p = sim.dem().particles();
  const PackingMetrics m = measure_packing(p, s.domain.width, s.domain.thickness);
  const double area = s.domain.width * s.domain.thickness;
  double mass = std::accumulate(p.mass.begin(), p.mass.end(), 0.0);
  return {sim.pressure_drop(), total_fluid_force_y(sim), total_drag_y(sim),
          mass * s.physics.gravity / area, m.bed_height, m.solid_fraction, area,
          s.gas.density * s.physics.gravity * s.domain.height * area};
}

}  // namespace

TEST(CoupledBed, NewtonsThirdLawHoldsAtEveryStep) {
  // A small jetted bed falling and blown: the drag on all particles and the force on the gas
  // cancel to round-off at every gas step, also when the gas is sub-stepped.
  for (int sub : {1, 3}) {
    Settings s = paper_bed();
    s.particles.placement = Placement::Lattice;
    s.particles.count = 300;
    s.particles.fill_height = 0.3;
    s.inlet.superficial_velocity = 1.5;
    s.coupling.particle_steps_per_gas_step = sub;
    Simulation sim(s);
    double worst = 0.0, drag = 0.0;
    for (int k = 0; k < 600; ++k) {
      sim.step();
      worst = std::max(worst, sim.coupling_diagnostics().third_law_error);
      drag = std::max(drag, std::fabs(sim.coupling_diagnostics().drag_total_y));
    }
    EXPECT_GT(drag, 1e-4);  // there is drag to balance
    EXPECT_LT(worst, 1e-12) << "sub-steps " << sub;
  }
}

TEST(CoupledBed, ParticleHoversAtItsTerminalVelocity) {
  // One sphere in an upward flow from a uniform distributor. The gas partly goes round the
  // sphere's cell, so the inflow that holds it is found on the fixed sphere first: the inflow at
  // which the fluid force on it (Di Felice drag from the same law, plus -V grad p) equals its
  // weight, by secant steps. Released in that flow, the sphere must hover.
  Settings s = paper_bed({"inlet.kind=uniform", "particles.placement=single", "particles.count=1"});
  s.particles.x = 0.075;
  s.particles.y = 0.15;
  const double m = paper_mass(), weight = m * s.physics.gravity;
  auto lift = [&](double U) {  // fluid force / weight on the fixed sphere, steady gas
    Settings f = s;
    f.particles.frozen = true;
    f.inlet.superficial_velocity = U;
    Simulation sim(f);
    for (int k = 0; k < 1500; ++k) sim.step();
    return sim.dem().particles().ext_fy[0] / weight;
  };
  // The terminal slip in free space (eps = 1) is the first guess.
  double u0 = terminal_slip_velocity(0.002, 2700.0, s.gas.density, s.gas.viscosity, 1.0,
                                     s.physics.gravity, true);
  double u1 = 1.05 * u0, f0 = lift(u0) - 1.0, f1 = lift(u1) - 1.0;
  for (int k = 0; k < 4 && std::fabs(f1) > 1e-4; ++k) {
    const double u2 = u1 - f1 * (u1 - u0) / (f1 - f0);
    u0 = u1;
    f0 = f1;
    u1 = u2;
    f1 = lift(u1) - 1.0;
  }
  std::printf("hovering: inflow %.4f m/s holds the fixed sphere (force / weight - 1 = %.1e)\n", u1, f1);
  ASSERT_LT(std::fabs(f1), 1e-3);
  s.inlet.superficial_velocity = u1;
  Simulation sim(s);
  for (int k = 0; k < 3000; ++k) sim.step();  // 45 ms released
  const Particles& p = sim.dem().particles();
  const double a = p.fy[0] / m;
  std::printf("hovering: acceleration %.4f m/s^2, velocity %.5f m/s, moved %.3g m after 45 ms\n",
              a, p.vy[0], p.y[0] - 0.15);
  EXPECT_LT(std::fabs(a), 0.01 * s.physics.gravity);
  EXPECT_LT(std::fabs(p.vy[0]), 0.01);
}

TEST(CoupledBed, FixedBedForceBalanceAndErgun) {
  const FixedBed b = fixed_bed(1.0);
  const double ergun = ergun_pressure_gradient(1.0, 1.0 - b.solid_fraction, 0.004, 1.205, 1.8e-5);
  std::printf("fixed bed at 1.0 m/s: dp %.1f Pa, dp A %.5f N, fluid force %.5f N (drag %.5f N, "
              "gas weight %.5f N), "
              "dp / H %.0f Pa/m, Ergun at eps %.3f: %.0f Pa/m\n", b.dp, b.dp * b.area,
              b.fluid_force, b.drag, b.gas_weight, b.dp / b.bed_height, 1.0 - b.solid_fraction, ergun);
  // dp A carries the particles and the gas in the column (rho_f g H A, 1.2 % of it here).
  EXPECT_NEAR(b.dp * b.area, b.fluid_force + b.gas_weight, 0.02 * b.fluid_force);
  EXPECT_NEAR(b.dp / b.bed_height, ergun, 0.25 * ergun);
}

TEST(CoupledBed, MinimumFluidizationFromTheModel) {
  // The fixed bed's fluid force against the inflow: the bed lifts where the force the model puts
  // on the particles (model A: drag and -V grad p; the paper's printed form: drag alone) reaches
  // the bed's weight. Secant search on the fixed bed's steady force.
  auto force_ratio = [](double U, bool model_a) {
    const FixedBed b = fixed_bed(U);
    return (model_a ? b.fluid_force : b.drag) / (b.weight_per_area * b.area);
  };
  auto umf = [&](bool model_a, double lo, double hi) {
    const RootBracket b = false_position(
        [&](double U) { return force_ratio(U, model_a) - 1.0; }, lo, hi, 6, 0.005);
    // The secant's root, not the bracket's middle: false position moves one end only on a convex
    // curve, so the bracket can stay wide while its moving end converges.
    return b.secant_root();
  };
  const double model_a = umf(true, 1.5, 2.3);
  const double printed = umf(false, 2.3, 4.5);
  std::printf("minimum fluidization of the packed bed: model A %.3f m/s, printed form %.3f m/s\n",
              model_a, printed);
  EXPECT_GT(model_a, 1.5);
  EXPECT_LT(model_a, 2.3);
  EXPECT_GT(printed, model_a);  // drag alone has to carry the whole weight
}
