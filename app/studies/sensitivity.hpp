#pragma once
// `fluidbed study sensitivity --scene SCENE --vary KEY=V1,V2 --vary KEY1,KEY2=A1:B1,A2:B2
// [--set KEY=V] [--until T] [--seeds N]`: which settings decide a scene's figures. The scene runs
// as given (the base point) and at each value of one varied key, or one tuple of keys, at a time,
// every run measured the same way (dp, the probes, the bed top, the regime, bubbles, the cycle
// verdicts, cost); with --seeds each point over N packings. study.csv holds every point's means
// and spreads, runs.csv every run, scenes/ the resolved scene of every point, one chart a varied
// key, and summary.md names which keys move which figures beyond two standard errors.
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed::app::study {

// One --vary: KEY=V1,V2,... or KEY1,KEY2=A1:B1,A2:B2 (a tuple of keys varied together). Values
// are TOML values as --set takes them; commas and colons inside brackets or quotes belong to the
// value ("diagnostics.probes=[[0.045,0.045]],[[0.045,0.1]]").
struct Variation {
  std::string text;                              // as given
  std::vector<std::string> keys;                 // "gas.cells_x", ...
  std::vector<std::vector<std::string>> values;  // one tuple per value, as many as keys
};
// InputError of one line naming the problem (no '=', an empty key or value, a tuple of the
// wrong length, a key given twice).
Variation parse_variation(const std::string& text);

// One point of the study: the base (variation -1) or one tuple of one variation.
struct SensitivityPoint {
  std::string label;                   // "base", "gas.cells_x,gas.cells_y=18:100"
  int variation = -1;                  // index into the variations; -1: the base
  std::size_t value = 0;               // index of its tuple in the variation
  std::vector<std::string> overrides;  // its --set beyond the base's: the tuple, and what is held
  std::string held;                    // what was held fixed for it, in words; empty: nothing
};

// The points, the base first, then each variation's tuples in order. Where varying a key alone
// would silently move another physical quantity, the physical one is held and said in `held`:
// time.dt (without coupling.particle_steps_per_gas_step) keeps the gas step in seconds, the
// nearest whole number of particle steps; contact.stiffness (without contact.damping) keeps the
// restitution, the damping scaled by sqrt(k / k_base).
std::vector<SensitivityPoint> sensitivity_points(const Settings& base,
                                                 const std::vector<Variation>& variations);

// The value of KEY ("section.key") in a scene, as its TOML text ("18", "2e-05", "'uniform'");
// empty when the scene has no such key.
std::string scene_value(const Settings& s, const std::string& key);

}  // namespace fluidbed::app::study
