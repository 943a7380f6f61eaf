#include "cli/commands.hpp"

#include <cstdlib>

namespace fluidbed::app {

std::string asset_dir() {
  if (const char* env = std::getenv("FLUIDBED_ASSETS")) return env;
  return FLUIDBED_ASSET_DIR;
}

}  // namespace fluidbed::app
