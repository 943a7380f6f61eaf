#pragma once
// A run's checkpoint: DIR/checkpoint/, from which `fluidbed run --resume DIR` finishes the run
// with the same bits as a run that was never stopped (the same timeseries.csv, summary.json
// numbers and state hash). It is written whole or not at all: into a folder of this process's own
// beside it, then renamed over the previous one. It holds
//   state.bin       the simulation (sim/state_file.hpp: particles with their contact history, the
//                   gas fields, the coupler's pending exchange, the place in the gas cycle)
//   run.bin         the run's accumulators: the last gas step's report, the particles' energy
//                   ledger, the recorder (timeseries rows, summary sums, the drop test's bounces),
//                   the wall time so far and the state hash to check the load against
//   timeseries.csv  the rows so far, for reading (run.bin holds them bit for bit)
//   scene.toml      the scene as run, every value resolved, --set lines applied
//   options.json    how the run was started: scene file, --set lines, end time, threads
//   where.json      for reading: the simulated time and step reached, the particle steps since
//                   the last gas step, the wall time so far
// and what the caller adds (run/run_folder.hpp: job.json, what decides the run besides its
// scene; the outputs' state, such as the pictures' and the tracked particles').
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "run/recorder.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {

struct Checkpoint {
  std::string folder;          // DIR/checkpoint
  std::string scene_toml;      // scene.toml
  nlohmann::json options;      // options.json
  nlohmann::json job;          // job.json (null when the checkpoint has none)
  std::string timeseries_csv;  // timeseries.csv: the rows so far, header included
  double wall = 0.0;           // s of wall time the run took up to the checkpoint
};

// Writes RUN_DIR/checkpoint/ of `sim` and `recorder` as they are after a step; `wall`: seconds of
// wall time so far. `add_files`, when given, writes the caller's own files into the folder being
// written (its path), before it takes the checkpoint's name. Throws InputError when it cannot be
// written.
void write_checkpoint(const std::string& run_dir, const Simulation& sim,
                      const RunRecorder& recorder, double wall, const std::string& scene_toml,
                      const nlohmann::json& options, bool bubbles,
                      const std::function<void(const std::string&)>& add_files = {});

// RUN_DIR's checkpoint (its scene and options); an InputError of one line when RUN_DIR is not a
// folder or holds no checkpoint.
Checkpoint read_checkpoint(const std::string& run_dir);
// Puts the checkpoint's state into `sim` (built from the checkpoint's scene): particles, gas,
// coupling, the last gas step's report and the energy ledger. InputError when it does not fit.
void restore_simulation(const Checkpoint& c, Simulation& sim);
// Puts the checkpoint's accumulators into `recorder` (built on the restored simulation).
void restore_recorder(const Checkpoint& c, RunRecorder& recorder);
// Whether RUN_DIR holds a checkpoint to resume from (its checkpoint/ folder, or the previous one
// set aside by a process killed while it replaced it).
bool has_checkpoint(const std::string& run_dir);
// Removes RUN_DIR's checkpoint (the run finished), with any left half-written or set aside by a
// process killed while it wrote one, and the half-written files of such a process (below).
void remove_checkpoint(const std::string& run_dir);
// Removes the files a killed process left half-written in RUN_DIR, its frames/ and its vtk/
// ("NAME.partial.PID", as write_file_atomically and render::write_png name them) when process
// PID no longer exists.
void remove_partial_files(const std::string& run_dir);

}  // namespace fluidbed
