#pragma once
// Running a simulation to an end time: the loop (steps, checks after each gas step, the
// callers' hooks) around a RunRecorder (run/recorder.hpp), which keeps the timeseries and the
// summary.
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "run/recorder.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {

struct RunOptions {
  double until = -1.0;  // s, simulated time to reach; < 0: the scene's time.end
  // Called about every progress_interval wall seconds with the simulation and the wall time so far.
  std::function<void(const Simulation&, double)> progress;
  double progress_interval = 0.5;  // s
  // Called after every step with the simulation (read only): frames, files and panels at exact
  // simulated times. It must not change the run; its cost counts in the wall time.
  std::function<void(const Simulation&)> on_step;
  // Checks after every gas step, on top of the solvers' own, each failing the run in words:
  // the gas CFL number above cfl_limit (a gas step longer than the flow can be followed), and a
  // cell porosity outside [porosity_min, 1]. Spheres in a slab one diameter thick pack no denser
  // than porosity 0.395 (hexagonal, 1 - pi / (3 sqrt 3)); 0.3 needs every sphere to overlap its
  // neighbours by 7 % of a diameter or more.
  double cfl_limit = 1.0;
  double porosity_min = 0.3;
  // The bubble analysis beside the run ([bubbles]: bubbles.csv, mixing.csv, summary `bubbles`).
  bool bubbles = false;
  // Called with every timeseries row as soon as it is recorded (the run folder's live
  // timeseries.csv, run/live_folder.hpp).
  std::function<void(const TimeseriesRow&)> on_row;
  // Asked after every step: true ends the run there, unfinished (an interrupt).
  std::function<bool()> stop;
  // Checkpoints (run/checkpoint.hpp): called with the simulation, the recorder and the run's wall
  // time so far every checkpoint_interval wall seconds (<= 0: never) once the run is expected to
  // take more than checkpoint_min_run wall seconds in all, and when `stop` ends the run. Where it
  // falls does not change the run.
  std::function<void(const Simulation&, const RunRecorder&, double)> checkpoint;
  double checkpoint_interval = 0.0;  // s
  double checkpoint_min_run = 0.0;   // s
  // A resumed run: called once on the new recorder, before the first step, to put back a
  // checkpoint's accumulators (run/checkpoint.hpp: restore_recorder); wall_before: the wall
  // seconds the run took before the checkpoint (they count in the summary's wall time).
  std::function<void(RunRecorder&)> restore;
  double wall_before = 0.0;  // s
};

struct RunResult {
  bool completed = true;  // false: stopped early by RunOptions::stop (the summary is not a result)
  nlohmann::json summary;
  std::vector<TimeseriesRow> rows;
  bool bubbles = false;              // the rows carry the bubble columns
  std::vector<BubbleRow> bubble_rows;  // bubbles.csv
  std::vector<MixingSample> mixing;  // mixing.csv
  PowerSpectrum dp_spectrum;         // dp_spectrum.csv (when ok)
  // The probes' points (diagnostics.probes; each row carries one value per probe) and their
  // spectra (dp_spectrum.csv's columns psd_probe_N).
  std::vector<ProbePoint> probes;
  std::vector<PowerSpectrum> probe_spectra;
};

// The run's checks, for a caller that steps `sim` itself (the Python module): before the first
// step, a starting state that is not finite; after each gas step, RunOptions' limits (the gas
// CFL number, the cells' porosity). Each throws SimulationFailure in words.
void check_start(const Simulation& sim);
void check_gas_step(const Simulation& sim, const RunOptions& o);

// Steps `sim` to the end time. Throws SimulationFailure when the run blows up.
RunResult run_simulation(Simulation& sim, const RunOptions& options);

// Writes DIR/summary.json and DIR/timeseries.csv (each complete or not at all), and
// DIR/dp_spectrum.csv (with a column per probe), DIR/bubbles.csv and DIR/mixing.csv when the run
// has them.
void write_run_outputs(const std::string& dir, const RunResult& r);

// timeseries.csv's header (with the bubble columns or not, and a column per probe) and one row
// of it (its probes' columns those the row carries), '\n' included.
std::string timeseries_header(bool bubbles, std::size_t probes = 0);
std::string timeseries_line(const TimeseriesRow& row, bool bubbles);

}  // namespace fluidbed
