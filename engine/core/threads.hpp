#pragma once
// How many threads a simulation uses inside a step. Results do not depend on it (the particle
// step gathers forces in a fixed order), only the speed does.
#include <algorithm>
#include <thread>

namespace fluidbed {

// requested <= 0: one per core.
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace fluidbed
