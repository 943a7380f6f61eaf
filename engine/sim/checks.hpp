#pragma once
// Inspection of a scene before a run (`fluidbed check`, and the refusals every running command
// applies before its first step): figures derived from the settings, warnings where accuracy
// falls, refusals where the run cannot be stable. Nothing is run; every figure is a closed form.
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed {

// The derived figures, SI units.
struct SceneFigures {
  double particle_mass = 0.0;          // kg, rho pi d^3 / 6
  double contact_duration_wall = 0.0;  // s, pi sqrt(m / kappa_n): a sphere on a wall
  double contact_duration_pair = 0.0;  // s, pi sqrt((m / 2) / kappa_n): two equal spheres
  double dt_over_tc_wall = 0.0;        // time.dt / contact_duration_wall
  double dt_over_tc_pair = 0.0;
  double restitution_wall = 0.0;  // from eta_n, kappa_n and m (0: overdamped)
  double restitution_pair = 0.0;  // ... and m / 2
  double weight_per_area = 0.0;   // Pa, N m g / (width thickness)
  bool gas = false;               // the figures below only with the gas on
  double jet_velocity = 0.0;      // m/s, U width / (jets jet_width) for a jet, else U
  double archimedes = 0.0;        // Ar = d^3 rho_g (rho_p - rho_g) g / mu^2
  double umf_wen_yu = 0.0;        // m/s, Wen & Yu (1966)
  double cell_dx = 0.0, cell_dy = 0.0;  // m, a gas cell (the plenum's rows included)
  double cell_dx_over_d = 0.0;    // gas cell width / particle diameter
  double cell_dy_over_d = 0.0;
  double gas_dt = 0.0;          // s, time.dt x coupling.particle_steps_per_gas_step
  double gas_cfl_at_jet = 0.0;  // jet_velocity gas_dt / min(dx, dy)
};

// The integrator study's measured limits for one integrator, as multiples of the sphere-wall
// contact duration t_c (sim/checks.cpp says where they were measured).
struct StepLimits {
  double accurate = 0.0;        // the largest step whose drop-test error stayed under 5 %
  double largest_stable = 0.0;  // the largest step measured stable
  double unstable = 0.0;        // the smallest step measured unstable: refused from here
};
StepLimits measured_step_limits(Integrator integrator);

// A Hertz-Mindlin contact's duration depends on how fast the spheres meet: `check` and the step's
// checks take it at an impact of 1 m/s (Lethe's characteristic speed for the same purpose; a
// fluidized bed's collisions are slower, their contacts longer, as t_c goes with v^(-1/5)).
inline constexpr double kHertzImpactSpeed = 1.0;  // m/s

// Wen & Yu (1966): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7, U_mf = Re_mf mu / (rho_g d). Their
// two constants are a fit of Ergun's equation at a porosity at minimum fluidization of about
// 0.4 (1 / (phi eps^3) = 14, (1 - eps) / (phi^2 eps^3) = 11 for spheres, phi = 1).
double wen_yu_umf(double diameter, double particle_density, double gas_density, double viscosity,
                  double gravity);

struct SceneCheck {
  SceneFigures figures;
  std::vector<std::string> warnings;  // each one line, with its reason
  std::vector<std::string> refusals;  // each one line, with its reason: the scene is not run
};

SceneCheck check_scene(const Settings& s);

// The figures, warnings and refusals as `fluidbed check` prints them (lines of text).
std::string describe_check(const Settings& s, const SceneCheck& c);

// What every running command calls before its first step: the first refusal as an InputError
// (one line). The warnings are kept, so that a failure of the run can name its likely cause
// (failure_hint).
void refuse_unsafe_scene(const Settings& s);

// "; likely cause: ..." for a SimulationFailure's one line (FAILURE, its what()), from what
// crossed its limit and the last scene given to refuse_unsafe_scene: a gas CFL number names the
// gas velocity (the scene's CFL warning when it has one, else the jet's velocity and the key to
// lower); any other failure names the scene's first warning about its step or contacts, else
// the first warning. Empty when nothing in the scene points at the cause. velocity_in_use (m/s):
// the superficial velocity the simulation failed at where a control changed it from the scene's
// (Python's superficial_velocity): the hint then names it, and the jet's velocity at it; < 0: the
// scene's.
std::string failure_hint(const std::string& failure, double velocity_in_use = -1.0);

}  // namespace fluidbed
