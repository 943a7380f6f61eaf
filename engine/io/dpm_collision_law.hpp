#pragma once
// fluidbed's contact law and drag law fitted to DPMFoam's models (for the OpenFOAM export,
// io/openfoam_export.hpp): the spring-slider-dashpot's moduli and damping, and the ratio of
// Wen-Yu drag to fluidbed's fluid force. Pure formulas, no files.
#include "scene/settings.hpp"

namespace fluidbed {

// fluidbed's contact law (kappa_n, eta_n, kappa_t, eta_t, gamma) as DPMFoam's
// pairSpringSliderDashpot / wallSpringSliderDashpot. Their normal force is
//   f_n = kN delta^b - alpha sqrt(M kN) delta^(1/4) (v_r . n),   kN = (4/3) sqrt(R*) E*
// with R* the effective radius (d/4 for two equal spheres, d/2 against a wall), M the effective
// mass (m/2, m) and E* the effective modulus (E / (2 (1 - nu^2)) for two equal spheres,
// 1 / ((1 - nu^2)/E + (1 - nu_w^2)/E_w) against a wall).
// - b = 1 and E, E_w chosen so that kN = kappa_n for pairs and walls: the normal spring is ours
//   exactly (kN's unit is then N/m).
// - The dashpot grows as delta^(1/4) (ours is constant): alpha (pair and wall separately) is set
//   so that the restitution of a head-on impact at reference_speed is ours (closed form for the
//   linear spring-dashpot); at other speeds it differs a little (restitution_slow/fast).
// - The tangential spring is Mindlin's, 8 G* sqrt(R* delta) (G* = G / (2 (2 - nu)),
//   G = E / (2 (1 + nu))): it grows with the overlap and, with E this small, is far softer than
//   kappa_t (kt_pair at the reference impact's peak overlap). nu = 0 makes it the stiffest the
//   model allows (nu enters nothing else). The tangential dashpot is the normal one (eta_t =
//   eta_n).
// - Coulomb's limit is mu |f_n| with the dashpot included; a sliding pair's tangential spring is
//   reset to zero (ours is held at the limit); the wall model keeps no tangential history.
struct DpmCollisionLaw {
  double youngs_modulus = 0.0;       // Pa, E of the particles (constantProperties)
  double poissons_ratio = 0.0;       // nu of the particles
  double wall_youngs_modulus = 0.0;  // Pa, E_w (wallSpringSliderDashpotCoeffs)
  double wall_poissons_ratio = 0.0;  // nu_w
  double b = 1.0;                    // exponent of the normal spring
  double alpha_pair = 0.0;           // pairSpringSliderDashpotCoeffs alpha
  double alpha_wall = 0.0;           // wallSpringSliderDashpotCoeffs alpha
  double mu = 0.0;                   // friction, pairs and walls
  int resolution_steps = 1;          // collisionResolutionSteps
  // What the numbers give (for the notes and the tests).
  double kn_pair = 0.0, kn_wall = 0.0;                    // N/m, = contact.stiffness
  double reference_speed = 1.0;                           // m/s, impact speed of the damping match
  double restitution_pair = 0.0, restitution_wall = 0.0;  // fluidbed's (and DPMFoam's at v_ref)
  double slow_speed = 0.1, fast_speed = 3.0;              // m/s
  double restitution_pair_slow = 0.0, restitution_pair_fast = 0.0;  // DPMFoam's at those speeds
  double peak_overlap_pair = 0.0;  // m, of a pair impact at the reference speed (undamped)
  double kt_pair = 0.0;            // N/m, DPMFoam's tangential spring at that overlap
};

DpmCollisionLaw dpm_collision_law(const Settings& s);

// Restitution of a head-on impact at `speed` (m/s) under DPMFoam's normal law above with b = 1:
// spring kn (N/m), effective mass (kg), damping alpha. Integrated numerically (RK4, 20000 steps
// per contact duration); the contact ends when the overlap returns to zero.
double dpm_restitution(double kn, double mass, double alpha, double speed);

// The ratio of DPMFoam's WenYuDrag to fluidbed's total fluid force in a uniform bed (model A:
// Di Felice drag / eps, the drag and the pressure-gradient force together) at porosity eps and
// superficial slip speed (m/s), for the notes and the tests.
double wen_yu_over_di_felice(const Settings& s, double eps, double superficial_slip);

}  // namespace fluidbed
