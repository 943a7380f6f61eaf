#pragma once
// The two ways a run ends early. Both carry one line for the user.
//   InputError        - the scene, an override or a file is wrong (exit status 2).
//   SimulationFailure - the numbers blew up (NaN, runaway overlap, ...): reported, never written
//                       out as a result (exit status 3).
#include <stdexcept>
#include <string>

namespace fluidbed {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

class SimulationFailure : public std::runtime_error {
 public:
  explicit SimulationFailure(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace fluidbed
