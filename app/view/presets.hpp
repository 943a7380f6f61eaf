#pragma once
// The stages of Fig. 6 as buttons and script commands: gas velocities as multiples of the
// scene's own minimum fluidization velocity (measured, run/umf_estimate.hpp), so a bed of
// lighter particles gets lower velocities. The multiples were chosen from the regime the bubble
// analysis reports for the teaching bed at each (docs/teaching.md).
#include <cstddef>
#include <string>

namespace fluidbed::app {

struct Preset {
  const char* name;     // the script's word
  const char* label;    // the button
  double umf_multiple;  // U / U_mf
  const char* what;     // what the class should see, one line
};

inline constexpr Preset kPresets[] = {
    {"fixed", "Fixed bed", 0.6, "the gas seeps through the packed bed; dp grows with U"},
    {"minimum", "Minimum fluidization", 1.0,
     "the gas just carries the bed's weight; a packed bed first holds dp above it (Fig. 6's peak)"},
    {"bubbling", "Bubbling", 1.15, "gas beyond U_mf rises through the bed as bubbles"},
    {"slugging", "Slugging", 1.5, "bubbles as wide as the bed lift plugs of particles"},
};

inline const Preset* find_preset(const std::string& name) {
  for (const Preset& p : kPresets)
    if (name == p.name) return &p;
  return nullptr;
}

inline std::string preset_names() {
  std::string s;
  for (const Preset& p : kPresets) s += (s.empty() ? "" : ", ") + std::string(p.name);
  return s;
}

}  // namespace fluidbed::app
