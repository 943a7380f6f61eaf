// fluidbed check SCENE [--set ...]: the scene's derived figures, warnings and refusals, nothing
// run (sim/checks.hpp). Exit 0 when the scene would run (warnings allowed), 2 when refused.
#include <cstdio>

#include "cli/commands.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

namespace fluidbed::app {

int check_command(const CheckArgs& a) {
  const Settings s = load_scene(a.scene, a.overrides);
  const SceneCheck c = check_scene(s);
  std::fputs(describe_check(s, c).c_str(), stdout);
  return c.refusals.empty() ? 0 : 2;
}

}  // namespace fluidbed::app
