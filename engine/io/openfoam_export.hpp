#pragma once
// A scene as an OpenFOAM v1912 DPMFoam case (`fluidbed export SCENE --to openfoam DIR`): the bed,
// its gas grid, jet and walls as a blockMesh; the particles at the scene's start as a manual
// injection; the contact law converted to DPMFoam's spring-slider-dashpot; Wen-Yu drag; air;
// the scene's dt and end time; a decomposition into 2 sub-domains and an Allrun script. Written
// for Debian's `openfoam` package (binaries in /usr/bin, WM_PROJECT_DIR=/usr/share/openfoam).
// No OpenFOAM needed to write it.
//
//   DIR/Allrun                          blockMesh, decomposePar, mpirun -np 2 DPMFoam -parallel,
//                                       reconstructPar (`./Allrun serial`: one process)
//   DIR/system/{blockMeshDict,controlDict,fvSchemes,fvSolution,decomposeParDict}
//   DIR/constant/{g,transportProperties,turbulenceProperties.air}
//   DIR/constant/kinematicCloudProperties  the particles' model; its header says what differs
//   DIR/constant/kinematicCloudPositions   one line per sphere (x y z, m)
//   DIR/0/{U.air,p}                     the gas at rest, the inlet, the outlet
//
// The slab: one cell through the thickness, front and back patches "empty". OpenFOAM then
// solves the gas in 2-D (cell volume dx dy thickness, as eq 23) and keeps the parcels on the
// mid-plane (it zeroes their velocity along the empty direction), which is fluidbed's planar
// model; slip walls would leave a 3-D gas one cell thick and let spheres touch the front and back
// walls through round-off, a contact fluidbed never has.
//
// What differs from fluidbed, as exactly as the formulas allow (said again in the case's header
// comment and in the notes, with the numbers of the scene): see dpm_collision_law and notes.
#include <functional>
#include <string>
#include <vector>

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

// Our linear spring-dashpot's restitution (closed form): exp(-pi z / sqrt(1 - z^2)),
// z = eta / (2 sqrt(k m)).
double linear_restitution(double kn, double eta, double mass);

// The ratio of DPMFoam's WenYuDrag to fluidbed's total fluid force in a uniform bed (model A:
// Di Felice drag / eps, the drag and the pressure-gradient force together) at porosity eps and
// superficial slip speed (m/s), for the notes and the tests.
double wen_yu_over_di_felice(const Settings& s, double eps, double superficial_slip);

struct OpenfoamCase {
  std::string dir;                 // the case folder
  std::string allrun;              // path of Allrun
  std::size_t particles = 0;       // spheres in kinematicCloudPositions
  std::vector<std::string> notes;  // what the case leaves out or changes, one line each
};

// Writes the case into DIR (created; files already there are replaced). Throws InputError for a
// scene the case cannot express (no [gas], a frozen bed) or a folder that cannot be written;
// a refusal writes nothing. A "packed" start is generated first when not cached (about 30 s;
// `notify` hears one line then).
OpenfoamCase write_openfoam_case(const Settings& s, const std::string& dir,
                                 const std::function<void(const std::string&)>& notify = {});

}  // namespace fluidbed
