#pragma once
// Wall time spent in each phase of a step (neighbour search, contacts, integration, porosity
// and drag, gas), for `fluidbed bench`'s split. A few steady_clock reads per step: negligible.
#include <array>
#include <chrono>
#include <cstdint>

namespace fluidbed {

enum class Phase : int { Neighbours, Contacts, Integration, Coupling, Gas, Count };

inline const char* phase_name(Phase p) {
  constexpr const char* names[] = {"neighbour search", "contacts", "integration",
                                   "porosity and drag", "gas"};
  return names[static_cast<int>(p)];
}

class PhaseTimes {
 public:
  using Clock = std::chrono::steady_clock;
  void add(Phase p, Clock::duration d) { ns_[static_cast<int>(p)] += d.count(); }
  double seconds(Phase p) const {
    return static_cast<double>(ns_[static_cast<int>(p)]) *
           (static_cast<double>(Clock::period::num) / Clock::period::den);
  }
  void reset() { ns_.fill(0); }

 private:
  std::array<std::int64_t, static_cast<int>(Phase::Count)> ns_{};
};

// Adds the time from construction (or the last lap) to a phase.
class PhaseClock {
 public:
  explicit PhaseClock(PhaseTimes& t) : t_(t), last_(PhaseTimes::Clock::now()) {}
  void lap(Phase p) {
    const auto now = PhaseTimes::Clock::now();
    t_.add(p, now - last_);
    last_ = now;
  }

 private:
  PhaseTimes& t_;
  PhaseTimes::Clock::time_point last_;
};

}  // namespace fluidbed
