#pragma once
// What this program is: the project's version (CMake's project VERSION) and the git commit its
// sources were built from. Defined in a file generated at every build (app/build_info.cmake)
// and rewritten only when the commit changes, so a new commit recompiles that file alone.
#include <string>
#include <string_view>

namespace fluidbed::app {

std::string_view version();  // "0.1.0"
// The commit's full hash; "unknown" when the sources were not a git checkout (or git was missing).
std::string_view commit();
// Whether tracked files differed from that commit when the program was built.
bool local_changes();
// "fluidbed 0.1.0 (commit HASH)", with ", with local changes" inside the brackets when so.
std::string version_line();

}  // namespace fluidbed::app
