// fluidbed export: a scene written as a case for another code, to run beds that outgrow one
// machine on LIGGGHTS with MPI and to compare the codes on the same work.
#include "export_command.hpp"

#include <cstdio>

#include "core/errors.hpp"
#include "io/liggghts_export.hpp"
#include "scene/scene_loader.hpp"

namespace fluidbed::app {

int export_command(const ExportArgs& a) {
  // The target first: a typo should not wait for the scene to load.
  if (a.to == "openfoam")
    throw InputError(
        "--to openfoam: not yet available (a DPMFoam case is planned); known: liggghts");
  if (a.to != "liggghts")
    throw InputError("--to \"" + a.to +
                     "\": unknown target; known: liggghts (openfoam is "
                     "planned, not yet available)");
  if (a.dir.empty()) throw InputError("export: give the output folder DIR");
  const Settings s = load_scene(a.scene, a.overrides);
  const LiggghtsCase c = write_liggghts_case(s, a.dir);
  std::printf("wrote %s and %s\n", c.deck.c_str(), c.data.c_str());
  for (const std::string& n : c.notes) std::printf("  note: %s\n", n.c_str());
  std::printf(
      "run it: cd %s && liggghts -in in.liggghts   (MPI: mpirun -np N liggghts -in "
      "in.liggghts)\n",
      a.dir.c_str());
  return 0;
}

}  // namespace fluidbed::app
