#pragma once
// A run's checkpoints with its outputs (run/checkpoint.hpp): `run` and the runs of `reproduce`
// keep the state of their pictures (output/frames.hpp) and tracked particles (output/plots.hpp)
// beside the simulation's, and resume all of it.
#include <nlohmann/json.hpp>
#include <string>

#include "output/frames.hpp"
#include "output/plots.hpp"
#include "run/checkpoint.hpp"
#include "run/run.hpp"

namespace fluidbed::app {

struct OutputCheckpoint {
  std::string dir;         // the run's folder: DIR/checkpoint/
  std::string scene_toml;  // the scene as run
  nlohmann::json options;  // options.json: how the run was started
  bool bubbles = false;    // the timeseries has the bubble columns
  FrameOutput* pictures = nullptr;            // its pictures.bin, when the run has pictures
  const TrajectoryRecorder* tracks = nullptr;  // its tracks.bin, when the run tracks particles
};

// Sets opt.checkpoint to write c.dir/checkpoint/ with the outputs' files, and for a run resumed
// from `resumed` (else nullptr) opt.restore and opt.wall_before. The interval is the caller's.
void checkpoint_with_outputs(RunOptions& opt, const OutputCheckpoint& c, const Checkpoint* resumed);

// The interval: every `every` wall seconds from the start (--checkpoint-every); below 0, the
// default: every 60 s once the run is expected to take more than two minutes.
void set_checkpoint_interval(RunOptions& opt, double every);

// A finished run's folder as an unstopped run leaves it: its checkpoint removed, then the video's
// parts (which the checkpoint names).
void remove_run_checkpoint(const std::string& dir);

}  // namespace fluidbed::app
