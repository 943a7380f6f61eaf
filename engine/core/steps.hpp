#pragma once
// Simulated times as counts of fixed time steps: the one rounding rule every part of the program
// uses (a run's last step, output rows, frames, script times, exported decks), so that they all
// agree on which step a time falls on.
#include <cmath>
#include <cstdint>

namespace fluidbed {

// The step nearest to `seconds` for a step of `dt` seconds (round half away from zero).
inline std::int64_t steps_for(double seconds, double dt) {
  return static_cast<std::int64_t>(std::llround(seconds / dt));
}

}  // namespace fluidbed
