#include "build_info.hpp"

namespace fluidbed::app {

std::string version_line() {
  return "fluidbed " + std::string(version()) + " (commit " + std::string(commit()) +
         (local_changes() ? ", with local changes)" : ")");
}

}  // namespace fluidbed::app
