#pragma once
// The run loop of `run` and `bench` with a progress line: on a terminal, stderr shows the
// simulated time reached, wall seconds per simulated second and particle-steps per second.
#include <functional>

#include "run/run.hpp"
#include "sim/simulation.hpp"

namespace fluidbed::app {

// run_simulation to `until` (s), `on_step` after every step (may be empty), with the bubble
// analysis when `bubbles`.
// on_row and stop: RunOptions' (run/run.hpp).
RunResult run_with_progress(Simulation& sim, double until,
                            std::function<void(const Simulation&)> on_step = {},
                            bool bubbles = false,
                            std::function<void(const TimeseriesRow&)> on_row = {},
                            std::function<bool()> stop = {});

// The same with every RunOptions field the caller set (its progress and until are set here).
RunResult run_with_progress(Simulation& sim, double until, RunOptions opt);

}  // namespace fluidbed::app
