// fluidbed export: a scene written as a case for another code, to run beds that outgrow one
// machine on LIGGGHTS or OpenFOAM with MPI and to compare the codes on the same work.
#include "cli/export.hpp"

#include <cstdio>

#include "core/errors.hpp"
#include "io/liggghts_export.hpp"
#include "io/openfoam_export.hpp"
#include "scene/scene_loader.hpp"

namespace fluidbed::app {
namespace {

int export_liggghts(const Settings& s, const std::string& dir) {
  const LiggghtsCase c = write_liggghts_case(s, dir);
  std::printf("wrote %s and %s\n", c.deck.c_str(), c.data.c_str());
  for (const std::string& n : c.notes) std::printf("  note: %s\n", n.c_str());
  std::printf(
      "run it: cd %s && liggghts -in in.liggghts   (MPI: mpirun -np N liggghts -in "
      "in.liggghts)\n",
      dir.c_str());
  return 0;
}

int export_openfoam(const Settings& s, const std::string& dir) {
  const OpenfoamCase c = write_openfoam_case(
      s, dir, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
  std::printf(
      "wrote the DPMFoam case %s (OpenFOAM v1912): %zu particles, %d x %d cells, "
      "dt = %g s to %g s\n",
      c.dir.c_str(), c.particles, s.gas.cells_x, s.gas.cells_y, s.time.dt, s.time.end);
  for (const std::string& n : c.notes) std::printf("  note: %s\n", n.c_str());
  std::printf(
      "run it: %s   (2 MPI processes: blockMesh, decomposePar, mpirun -np 2 DPMFoam -parallel, "
      "reconstructPar; `%s serial`: one process)\n",
      c.allrun.c_str(), c.allrun.c_str());
  return 0;
}

}  // namespace

int export_command(const ExportArgs& a) {
  // The target first: a typo should not wait for the scene to load.
  if (a.to != "liggghts" && a.to != "openfoam")
    throw InputError("--to \"" + a.to + "\": unknown target; known: liggghts, openfoam");
  if (a.dir.empty()) throw InputError("export: give the output folder DIR");
  const Settings s = load_scene(a.scene, a.overrides);
  return a.to == "liggghts" ? export_liggghts(s, a.dir) : export_openfoam(s, a.dir);
}

}  // namespace fluidbed::app
