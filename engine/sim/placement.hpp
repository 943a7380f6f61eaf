#pragma once
// Initial particles of a scene: the paper's random lattice start, one particle, or a saved state.
#include "dem/dem_solver.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

// Particles placed as the scene says (at rest unless "single" gives a velocity).
Particles place_particles(const Settings& s);

// For placement = "state": the saved state, checked against the scene (count, size) and with
// masses taken from the scene's density.
DemState load_scene_state(const Settings& s);

// Resolves a path from a scene relative to the scene file's folder.
std::string scene_path(const Settings& s, const std::string& path);

}  // namespace fluidbed
