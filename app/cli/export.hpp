#pragma once
// fluidbed export SCENE --to liggghts|openfoam DIR: the scene as another code's case (see
// engine/io/liggghts_export.hpp and openfoam_export.hpp for what each keeps and leaves out).
#include <string>
#include <vector>

namespace fluidbed::app {

struct ExportArgs {
  std::string scene;                   // scene file
  std::vector<std::string> overrides;  // --set section.key=value
  std::string to;                      // target code: "liggghts" or "openfoam"
  std::string dir;                     // output folder, created when missing
};

// Writes the case and prints what was written, what the case leaves out and how to run it.
// Returns 0; an unknown --to, a bad scene or a scene the target cannot express throw InputError.
int export_command(const ExportArgs& a);

}  // namespace fluidbed::app
