#pragma once
// The three time integrators of the particle step, each split around the force evaluation:
// `predict` runs before the forces (the predictor, or kick-drift), `correct` after them (the
// corrector, kick, or Euler update). One loop per integrator over a range of particles, no
// per-particle branch; the solver picks the integrator once per run.
//
//   Newmark (the paper's predictor-corrector, eqs 24-28 with alpha = 1/2, beta = 1/4): predict
//     x += h v + h^2/4 a, v += h/2 a; evaluate the forces there; correct with the new a.
//   Velocity Verlet: kick half a step, drift, forces at the new positions, kick half a step.
//   Symplectic Euler: forces first, then v += h a, x += h v.
#include <cstddef>

#include "dem/particles.hpp"
#include "scene/options.hpp"  // Integrator

namespace fluidbed {

// Particles [b, e) before the forces of a step of h seconds.
void predict(Integrator integrator, double h, Particles& p, std::size_t b, std::size_t e);
// Particles [b, e) after the forces (Particles::fx, fy, torque) of the same step: the new
// accelerations (ax, ay, aw) and the step's end state.
void correct(Integrator integrator, double h, Particles& p, std::size_t b, std::size_t e);

}  // namespace fluidbed
