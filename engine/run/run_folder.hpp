#pragma once
// A run in a folder: one simulation to its end time in DIR, resumably. Every verb that runs a
// simulation into a folder (`run`, `run --seeds`, `sweep`, `reproduce`, the studies' points)
// describes its run as a RunJob and calls run_in_folder, which owns, in this order:
//   - the finished run: with RunControl::resume, a folder whose marker says it finished (or
//     failed) is read back instead of run again;
//   - the identity check: a run resumed from DIR/checkpoint/ must be the same run (the scene as
//     run, the end time, the bubble analysis, the start state; one line naming what changed);
//   - the packed bed, the Simulation, and its restore from the checkpoint (run/checkpoint.hpp);
//   - the outputs attached to the job (run/run_output.hpp), started or restored;
//   - the live folder (run/live_folder.hpp): DIR/status.json and DIR/timeseries.csv as it goes;
//   - the run (run/run_loop.hpp) with its checkpoints, periodic and at a stop request;
//   - at the end: the outputs' files, DIR/summary.json, timeseries.csv, dp_spectrum.csv,
//     bubbles.csv and mixing.csv, the final state when asked for, the checkpoint removed, and
//     last the finished marker.
//
// The finished marker is DIR/status.json with "status": "completed" (or "failed", with the
// reason), the wall time, a digest of the job and the outputs' `result` figures. A folder whose
// status.json says "running" holds a run that is going, or was killed; "interrupted" one stopped
// with a checkpoint.
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "run/run_loop.hpp"
#include "run/run_output.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

struct RunJob {
  Settings scene;        // as run (threads set); a packed placement is made ready here
  double until = -1.0;   // s; < 0: the scene's time.end
  bool bubbles = false;  // the bubble analysis beside the recorder
  // Continue from this state file (particles, contacts, gas: a sweep's decreasing branch)
  // instead of the scene's own start.
  std::string start_state;
  // How the caller started the run, kept in the checkpoint as options.json (`run --resume`
  // reads its arguments back from there); not part of the identity.
  nlohmann::json started = nlohmann::json::object();
  // DIR/scene.toml's header (comment lines, each ending in '\n') before the scene as run;
  // empty: no scene.toml.
  std::string scene_note;
  // The final state as DIR/<final_state> (empty: none), with the scene's
  // diagnostics.save_state beside it when that is set.
  std::string final_state;
  std::vector<std::unique_ptr<RunOutput>> outputs;
};

struct RunControl {
  // Read a finished run back, continue a stopped one from its checkpoint; else a new run (an
  // earlier run's checkpoint in DIR is removed).
  bool resume = false;
  // Wall seconds between checkpoints; < 0: every 60 s once the run is expected to take more than
  // two minutes; 0: none but the one a stop writes.
  double checkpoint_every = -1.0;
  std::function<bool()> stop;  // asked after every step: true stops the run with a checkpoint
  std::function<std::string()> stop_reason;  // for status.json ("stopped by SIGINT")
  // About every half wall second: the simulation and the run's wall time so far.
  std::function<void(const Simulation&, double)> progress;
  // Lines for the user ("resumed at t = 0.25 s"); may be empty.
  std::function<void(const std::string&)> log;
};

struct RunEnd {
  enum class How { finished, stopped, failed };
  How how = How::finished;
  RunResult result;   // finished: everything; read back: the summary alone
  std::string error;  // failed: the failure's words
  double wall = 0.0;  // s, the whole run's (a resumed run's earlier parts included)
  double cpu = 0.0;   // s, CPU time of the calling thread while this process stepped it
  double t = 0.0;     // s, the simulated time reached
  nlohmann::json record = nlohmann::json::object();  // the marker's `result` (outputs' figures)
  bool read_back = false;  // it had ended before: read back from its folder
  bool resumed = false;    // read back, or continued from its checkpoint

  bool finished() const { return how == How::finished; }
};

// Runs (or reads back, or continues) the job in DIR. The job's outputs stay the caller's to ask
// after the run (what they wrote, their costs). A SimulationFailure ends the run as failed (the
// marker says so; not thrown); InputError is thrown (bad options, a checkpoint of another run, a
// folder that cannot be written).
RunEnd run_in_folder(const std::string& dir, RunJob& job, const RunControl& control);

// DIR/status.json as written last by a run (or a study), if any.
std::optional<nlohmann::json> read_run_status(const std::string& dir);
// Whether DIR holds an ended run (status completed or failed) that a resumed job may read back.
bool run_ended(const std::string& dir);

}  // namespace fluidbed
