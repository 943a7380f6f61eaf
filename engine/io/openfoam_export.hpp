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
// The slab: one cell through the thickness. A monolayer's front and back patches are "empty":
// OpenFOAM then solves the gas in 2-D (cell volume dx dy thickness, as eq 23) and keeps the
// parcels on the mid-plane (it zeroes their velocity along the empty direction), which is
// fluidbed's planar model. A thick slab (slab_has_depth) is written with its spheres' depths and
// the front and back as wall patches: walls for the spheres (the side walls' spring-slider-
// dashpot), slip for the gas, so that the gas is still 2-D through the depth as fluidbed's is.
// A scene with the Hertz-Mindlin law is refused (the case is written for the linear spring).
//
// What differs from fluidbed, as exactly as the formulas allow (said again in the case's header
// comment and in the notes, with the numbers of the scene): see io/dpm_collision_law.hpp and
// the notes.
#include <functional>
#include <string>
#include <vector>

#include "io/dpm_collision_law.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

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
