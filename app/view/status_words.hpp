#pragma once
// What the panel says of the engine, in words a class understands (no ImGui, so tests can read
// them): whether the bed is running, and its speed as slow motion beside the measured figure.
#include <string>

#include "view/engine.hpp"

namespace fluidbed::app {

// "running", "paused", "running to t = 0.300 s (script)", "stopped: the simulation failed".
// `script_runs_it`: a script is running the bed from one `at T` to the next (it is running even
// at the instant it stopped there for a screenshot).
std::string run_state_words(const EngineStatus& st, bool script_runs_it);
// "slow motion x 15.0 (0.0667 sim s per wall s)", "real time (1.02 sim s per wall s)",
// "fast motion x 2.0 (2 sim s per wall s)", "speed: not measured yet". One line of the panel.
std::string speed_words(double sim_s_per_wall_s);
// The same for the presenter mode, without the figure: "slow motion: 1 s of the bed takes 2.3 s
// here", "real time"; empty before it is measured.
std::string speed_for_a_class(double sim_s_per_wall_s);

}  // namespace fluidbed::app
