#pragma once
// The verbs of the command line. Each returns the process exit status; input errors and
// simulation failures propagate as exceptions and are turned into statuses 2 and 3 by main.
#include <string>
#include <vector>

namespace fluidbed::app {

struct RunArgs {
  std::string scene;
  std::vector<std::string> overrides;
  double until = -1.0;  // s, < 0: the scene's time.end
  std::string out;      // output folder; empty: out/<scene file name>
};

int run_command(const RunArgs& a);
int bench_command(const RunArgs& a);

// The shipped assets folder (scenes, fonts): $FLUIDBED_ASSETS, else the source tree's.
std::string asset_dir();

}  // namespace fluidbed::app
