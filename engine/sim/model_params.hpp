#pragma once
// The one place where a scene's settings become the parameters of each part of the model: the
// particle solver, the gas solver and its grid, and the coupler. Each part then knows only its
// own struct (as LAMMPS resolves sub-model names once at setup and Lethe hands each solver its
// own parameters), so a setting is read in one place.
#include "cfd/gas_grid.hpp"
#include "cfd/gas_solver.hpp"
#include "coupling/coupler.hpp"
#include "dem/dem_solver.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

// contact.renumber_steps = -1: the particles are renumbered by cell every kAutoRenumberSteps
// steps when their arrays (Particles::bytes_per_particle) take kAutoRenumberBytes or more:
// twice the 512 kB of a core's second-level cache on the machines measured. Measured
// (docs/speed.md): the paper's bed (2,400 spheres, 0.33 MB) gains nothing, van Wachem's (17,562
// in a thick slab, 3.9 MB) 1.13 x, a bed of 240,000 mixed 1.4 x with the gas.
inline constexpr double kAutoRenumberBytes = 1024.0 * 1024.0;
inline constexpr int kAutoRenumberSteps = 1000;

DemParams dem_params_for(const Settings& s);
GasGrid gas_grid_for(const Settings& s);
GasParams gas_params_for(const Settings& s);
CouplerParams coupler_params_for(const Settings& s);

}  // namespace fluidbed
