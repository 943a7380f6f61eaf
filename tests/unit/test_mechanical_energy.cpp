// The mechanical energy of a particle state (the integrator study's measure) against hand
// calculation, and its pair search against all pairs.
#include <gtest/gtest.h>

#include <cmath>

#include "../test_support.hpp"
#include "analysis/mechanical_energy.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

TEST(MechanicalEnergy, KineticPotentialAndElasticByHand) {
  // Two spheres overlapping by 10 um, one moving and spinning, one touching the floor by 5 um.
  Particles p = make_particles({{0.05, 0.02, 0.3, -0.4, 10.0}, {0.05 + 0.004 - 1e-5, 0.02, 0.0, 0.0, 0.0},
                                {0.10, 0.002 - 5e-6, 0.0, 0.0, 0.0}});
  DomainSettings d;
  const auto walls = slab_walls(d);
  const double k = 50000.0, g = 9.81, m = paper_mass(), r = 0.002;
  const MechanicalEnergy e = mechanical_energy(p, walls, k, g);
  const double inertia = 0.4 * m * r * r;
  EXPECT_NEAR(e.kinetic, 0.5 * m * (0.09 + 0.16) + 0.5 * inertia * 100.0, 1e-15);
  EXPECT_NEAR(e.potential, m * g * (0.02 + 0.02 + 0.002 - 5e-6), 1e-15);
  EXPECT_NEAR(e.elastic, 0.5 * k * (1e-5 * 1e-5 + 5e-6 * 5e-6), 1e-14);
}

TEST(MechanicalEnergy, PairSearchFindsEveryOverlapOfARandomHeap) {
  Particles p;
  p.resize(400);
  std::uint64_t state = 12345;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.set_sphere(i, 0.004, 2700.0);
    p.x[i] = 0.01 + 0.08 * uniform();
    p.y[i] = 0.01 + 0.08 * uniform();
  }
  double brute = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double d = std::hypot(p.x[j] - p.x[i], p.y[j] - p.y[i]);
      if (d < 0.004) brute += 0.5 * 1000.0 * (0.004 - d) * (0.004 - d);
    }
  const MechanicalEnergy e = mechanical_energy(p, {}, 1000.0, 0.0);
  EXPECT_GT(brute, 0.0);
  EXPECT_NEAR(e.elastic, brute, 1e-12 * brute);
}

TEST(MechanicalEnergy, NonFiniteStateGivesNonFiniteTotal) {
  Particles p = make_particles({{0.05, 0.02, NAN, 0.0, 0.0}});
  EXPECT_FALSE(std::isfinite(mechanical_energy(p, {}, 1000.0, 9.81).total()));
}
