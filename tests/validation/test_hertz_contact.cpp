// The Hertz-Mindlin contact (contact.law = "hertz_mindlin", a thick slab) against closed forms:
// an elastic impact lasts Hertz's duration and reaches his largest overlap, on a wall and between
// two spheres meeting off the plane, with the springs' stored energy (DemSolver::spring_energy)
// accounting for the kinetic energy in between; a damped one rebounds with the restitution of the
// law integrated finely, the same at every speed (the point of Tsuji's dashpot).
// (A Hertz slab packed on one and two threads: test_thick_slab.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../test_support.hpp"
#include "dem/dem_solver.hpp"
#include "sim/model_params.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

constexpr double kE = 1.0e7, kNu = 0.3;  // Lethe's van Wachem material, on the paper's spheres
constexpr double kR = 0.002;

// A box 0.2 x 0.2 x 0.04 m without gravity, Hertz-Mindlin of restitution e, step dt.
Settings hertz_box(double e, double dt) {
  Settings s;
  s.domain.width = 0.2;
  s.domain.height = 0.2;
  s.domain.thickness = 0.04;
  s.physics.gravity = 0.0;
  s.contact.law = ContactLaw::HertzMindlin;
  s.contact.youngs_modulus = kE;
  s.contact.poisson_ratio = kNu;
  s.contact.restitution = e;
  s.contact.friction = 0.0;
  s.time.dt = dt;
  return s;
}

// Spheres of the paper's size at (x, y, z) with velocity (vx, vy, vz).
Particles spheres(std::initializer_list<std::array<double, 6>> list) {
  Particles p;
  p.resize(list.size());
  p.add_depth(0.0);
  std::size_t i = 0;
  for (const auto& q : list) {
    p.set_sphere(i, 2.0 * kR, 2700.0);
    p.x[i] = q[0];
    p.y[i] = q[1];
    p.z[i] = q[2];
    p.vx[i] = q[3];
    p.vy[i] = q[4];
    p.vz[i] = q[5];
    ++i;
  }
  return p;
}

double kinetic(const Particles& p) {
  double k = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    k += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
  return k;
}

// What an impact did: its duration (s, steps in contact times dt), largest overlap (m), the
// largest relative error of kinetic + spring energy against the start's, and the state after.
struct Impact {
  double duration = 0.0, max_overlap = 0.0, energy_error = 0.0;
};
template <class Overlap>
Impact run_impact(DemSolver& dem, double dt, double seconds, Overlap overlap) {
  Impact m;
  const double e0 = kinetic(dem.particles());
  const auto steps = static_cast<std::int64_t>(seconds / dt);
  for (std::int64_t k = 0; k < steps; ++k) {
    dem.step();
    const double o = overlap(dem.particles());
    if (o > 0.0) m.duration += dt;
    m.max_overlap = std::max(m.max_overlap, o);
    const SpringEnergy s = dem.spring_energy();
    const double e = kinetic(dem.particles()) + s.normal + s.tangential;
    m.energy_error = std::max(m.energy_error, std::fabs(e - e0) / e0);
  }
  return m;
}

// Hertz's largest overlap at an impact speed v: (15 m v^2 / (16 Y* sqrt(R)))^(2/5).
double hertz_overlap(double hertz_kn, double r_eff, double m_eff, double v) {
  const double y_eff = 0.75 * hertz_kn;
  return std::pow(15.0 * m_eff * v * v / (16.0 * y_eff * std::sqrt(r_eff)), 0.4);
}

}  // namespace

TEST(HertzContact, ElasticWallImpactLastsHertzsDurationAndReachesHisOverlap) {
  const double v = 1.0, m = paper_mass();
  ContactParams law;
  set_hertz(law, kE, kNu, 1.0);
  const double tc = hertz_contact_duration(law.hertz_kn, kR, m, v);
  const double dt = tc / 4000.0;
  Settings s = hertz_box(1.0, dt);
  DemSolver dem(dem_params_for(s), spheres({{0.1, 0.1, kR + 1e-5, 0.0, 0.0, -v}}));
  const Impact got =
      run_impact(dem, dt, 1e-5 / v + 1.5 * tc, [](const Particles& p) { return kR - p.z[0]; });
  const double overlap = hertz_overlap(law.hertz_kn, kR, m, v);
  std::printf(
      "wall: t_c %.6e s (Hertz %.6e), overlap %.6e m (%.6e), rebound %.6f m/s, energy "
      "within %.1e\n",
      got.duration, tc, got.max_overlap, overlap, dem.particles().vz[0], got.energy_error);
  EXPECT_NEAR(got.duration, tc, 2e-3 * tc);
  EXPECT_NEAR(got.max_overlap, overlap, 1e-3 * overlap);
  EXPECT_NEAR(dem.particles().vz[0], v, 1e-4 * v);
  EXPECT_LT(got.energy_error, 1e-3);
}

TEST(HertzContact, ElasticPairImpactOffThePlaneLastsHertzsDuration) {
  // Two spheres meeting head-on at 1 m/s along a line out of every coordinate plane: R* = R / 2,
  // m* = m / 2.
  const double v = 1.0, m = paper_mass();
  const double d[3] = {0.6, 0.48, 0.64};
  ContactParams law;
  set_hertz(law, kE, kNu, 1.0);
  const double tc = hertz_contact_duration(law.hertz_kn, 0.5 * kR, 0.5 * m, v);
  const double dt = tc / 4000.0, gap = 2.0 * kR + 1e-5;
  Settings s = hertz_box(1.0, dt);
  DemSolver dem(dem_params_for(s),
                spheres({{0.1, 0.1, 0.02, 0.5 * v * d[0], 0.5 * v * d[1], 0.5 * v * d[2]},
                         {0.1 + gap * d[0], 0.1 + gap * d[1], 0.02 + gap * d[2], -0.5 * v * d[0],
                          -0.5 * v * d[1], -0.5 * v * d[2]}}));
  auto overlap = [](const Particles& p) {
    const double dx = p.x[1] - p.x[0], dy = p.y[1] - p.y[0], dz = p.z[1] - p.z[0];
    return 2.0 * kR - std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  const Impact got = run_impact(dem, dt, 1e-5 / v + 1.5 * tc, overlap);
  const Particles& p = dem.particles();
  const double apart =
      (p.vx[1] - p.vx[0]) * d[0] + (p.vy[1] - p.vy[0]) * d[1] + (p.vz[1] - p.vz[0]) * d[2];
  const double overlap_h = hertz_overlap(law.hertz_kn, 0.5 * kR, 0.5 * m, v);
  std::printf(
      "pair: t_c %.6e s (Hertz %.6e), overlap %.6e m (%.6e), separating at %.6f m/s, "
      "energy within %.1e\n",
      got.duration, tc, got.max_overlap, overlap_h, apart, got.energy_error);
  EXPECT_NEAR(got.duration, tc, 2e-3 * tc);
  EXPECT_NEAR(got.max_overlap, overlap_h, 1e-3 * overlap_h);
  EXPECT_NEAR(apart, v, 1e-4 * v);
  EXPECT_LT(got.energy_error, 1e-3);
}

TEST(HertzContact, DampedWallImpactRestitutesAsTheLawIntegratedFinelyAtEverySpeed) {
  // The law's restitution, from the head-on ODE m x'' = -kn(x) x - eta_n(x) x' integrated by RK4
  // at a hundred thousand steps per contact, independently of the engine's step and history.
  const double e_in = 0.9, m = paper_mass();
  ContactParams law;
  set_hertz(law, kE, kNu, e_in);
  auto ode = [&](double v0) {
    auto acc = [&](double x, double u) {
      const ContactParams c = hertz_params(law, x, kR, m);
      return (-c.kn * std::max(x, 0.0) - c.eta_n * u) / m;
    };
    const double h = hertz_contact_duration(law.hertz_kn, kR, m, v0) / 1e5;
    double x = 0.0, u = v0;
    while (x >= 0.0) {
      const double k1x = u, k1u = acc(x, u);
      const double k2x = u + 0.5 * h * k1u, k2u = acc(x + 0.5 * h * k1x, u + 0.5 * h * k1u);
      const double k3x = u + 0.5 * h * k2u, k3u = acc(x + 0.5 * h * k2x, u + 0.5 * h * k2u);
      const double k4x = u + h * k3u, k4u = acc(x + h * k3x, u + h * k3u);
      x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
      u += h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
    }
    return -u / v0;
  };
  const double e_ode = ode(1.0);
  EXPECT_NEAR(e_ode, e_in, 1e-3);  // Tsuji's dashpot gives the restitution it was built from
  for (const double v : {0.2, 1.0, 3.0}) {
    const double tc = hertz_contact_duration(law.hertz_kn, kR, m, v);
    const double dt = tc / 2000.0;
    Settings s = hertz_box(e_in, dt);
    DemSolver dem(dem_params_for(s), spheres({{0.1, 0.1, kR + 1e-6, 0.0, 0.0, -v}}));
    const auto steps = static_cast<std::int64_t>((1e-6 / v + 1.5 * tc) / dt);
    for (std::int64_t k = 0; k < steps; ++k) dem.step();
    const double e = dem.particles().vz[0] / v;
    std::printf(
        "v %.1f m/s: restitution %.6f (the law integrated finely %.6f at 1 m/s, %.6f "
        "here; the input %.2f)\n",
        v, e, e_ode, ode(v), e_in);
    EXPECT_NEAR(e, e_ode, 1e-3) << v;
  }
}
