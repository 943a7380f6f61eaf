#pragma once
// The mechanical energy of the particles, from their state alone: kinetic (translation and spin),
// gravitational (m g y) and elastic (1/2 kappa_n delta^2 over the geometric overlaps of pairs and
// walls). For a frictionless, undamped contact law it is conserved by the exact motion, so its
// change over a run measures an integrator's energy error (the integrator study's packing test).
// The elastic part uses the geometric overlap R_i + R_j - L whatever the contact form: with the
// incremental displacements (eqs 13-17) a spring that drifts from the geometry shows as energy
// gained or lost, which is what the comparison is for.
#include <vector>

#include "dem/particles.hpp"
#include "dem/walls.hpp"

namespace fluidbed {

struct MechanicalEnergy {
  double kinetic = 0.0;    // J, translation and spin about z
  double potential = 0.0;  // J, m g y
  double elastic = 0.0;    // J, normal springs of pairs and walls
  double total() const { return kinetic + potential + elastic; }
};

// kn: the normal spring constant (N/m) of pairs and walls. A non-finite position or velocity
// gives a non-finite total.
MechanicalEnergy mechanical_energy(const Particles& p, const std::vector<Wall>& walls, double kn,
                                   double gravity);

}  // namespace fluidbed
