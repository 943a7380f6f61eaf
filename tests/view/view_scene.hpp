#pragma once
// A small coupled bed for the viewer's tests: about a hundred particles on the lattice start with
// a jet, so that the engine thread steps in microseconds (also under the thread sanitizer); and
// the error a view script's text gives.
#include <string>

#include "core/errors.hpp"
#include "scene/scene_loader.hpp"

namespace fluidbed::testing {

inline const char* kViewTestScene = R"(
[scene]
name = "view_test"
[domain]
width = 0.04
height = 0.12
[particles]
count = 100
fill_height = 0.05
[gas]
cells_x = 4
cells_y = 12
[inlet]
kind = "jet"
superficial_velocity = 2.0
jet_width = 0.01
[coupling]
particle_steps_per_gas_step = 2
[time]
end = 1.0
)";

inline Settings view_test_settings() {
  return parse_scene(kViewTestScene, "view_test");
}

// A small bed shaped like the paper's (six times as high as wide), so that a window shows it with
// its close-up beside it, as it shows the paper's bed.
inline const char* kViewTallScene = R"(
[scene]
name = "view_tall"
[domain]
width = 0.03
height = 0.18
[particles]
count = 90
fill_height = 0.07
[gas]
cells_x = 3
cells_y = 18
[inlet]
kind = "jet"
superficial_velocity = 2.0
jet_width = 0.006
[coupling]
particle_steps_per_gas_step = 2
[time]
end = 1.0
)";

// The one-line error parsing TEXT as a view script gives ("no error" when it parses).
template <class Parse>
std::string script_error(Parse parse, const std::string& text) {
  try {
    parse(text, "s.txt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace fluidbed::testing
