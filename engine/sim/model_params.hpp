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

DemParams dem_params_for(const Settings& s);
GasGrid gas_grid_for(const Settings& s);
GasParams gas_params_for(const Settings& s);
CouplerParams coupler_params_for(const Settings& s);

}  // namespace fluidbed
