#pragma once
// The progress line of `run` and `bench`: on a terminal, stderr shows the simulated time
// reached, wall seconds per simulated second and particle-steps per second.
#include <functional>

#include "run/run_loop.hpp"
#include "sim/simulation.hpp"

namespace fluidbed::app {

using ProgressFn = std::function<void(const Simulation&, double)>;

// A progress callback (RunOptions::progress, RunControl::progress) for a run to `until` (s) that
// rewrites one line on stderr when stderr is a terminal; empty otherwise.
ProgressFn progress_printer(double until);
// Ends that line (a newline) when there was one.
void end_progress(const ProgressFn& progress);

// run_simulation to `until` (s) with the progress line.
RunResult run_with_progress(Simulation& sim, double until);

}  // namespace fluidbed::app
