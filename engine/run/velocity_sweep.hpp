#pragma once
// The paper's velocity sweep (Fig. 6). Increasing branch: each velocity starts from the packed
// bed. Decreasing branch: each velocity starts from the final state (particles, contacts and gas)
// of the lowest finished run above it; it begins at the highest velocity whose increasing run
// finished, which both branches share (a bed blown out of the top at the highest velocities
// still gets its decreasing branch, from below them).
// The mean pressure drop of each run is eq 30 over its settled part. Runs of the increasing
// branch are independent and run in parallel; the decreasing chain runs beside them.
//
// Each run's folder, OUT/runs/BRANCH-U/, is a run in a folder (run/run_folder.hpp): its usual
// files, final.state and, once the run ended (finished or failed), its finished marker
// status.json (with the configuration hashes at its start and end). A run stopped by `stop`
// leaves checkpoint/ (run/checkpoint.hpp) instead. OUT/sweep.json says what the sweep is (the
// resolved scene, the velocities, the run and averaging times, the caller's `command`): a
// resumed sweep must be the same sweep. Resumed, a run that ended is read back, a run with a
// checkpoint continues from it, the rest run; the result is the uninterrupted sweep's, bit for
// bit.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/umf_fit.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

struct SweepOptions {
  std::vector<double> velocities;  // m/s, superficial; empty: default_sweep_velocities(scene)
  double run_time = 2.0;           // s, simulated per velocity
  double averaging_start = 0.5;    // s into each run: tau_1 of eq 30
  int threads = 2;                 // runs at once
  std::string out_dir;             // per-run outputs and states go under it (required)
  std::function<void(const std::string&)> log;  // one line per finished run (may be empty)
  // Resume the sweep in out_dir (InputError when out_dir holds no sweep or another one).
  bool resume = false;
  // Asked after every step of every run: true stops each running run there with a checkpoint,
  // starts no other, and the result says interrupted.
  std::function<bool()> stop;
  double checkpoint_interval = 60.0;  // wall s between a running run's checkpoints (<= 0: only at stop)
  nlohmann::json command;             // how the caller started the sweep (kept in sweep.json)
  // Only what U_mf needs: the highest velocity from the scene's start, then the decreasing chain
  // from it (no hysteresis loop; the runs below the top of `up` are not run). Half the runs.
  bool decreasing_only = false;
};

struct SweepPoint {
  std::string branch;  // "up" or "down"
  double u = 0.0;      // m/s
  bool ok = false;
  std::string error;   // why the run failed (a SimulationFailure's words)
  double dp_mean = 0.0, dp_std = 0.0;  // Pa
  double wall_time = 0.0;              // s
  std::uint64_t start_hash = 0, end_hash = 0;  // particle configuration hashes (hand-over)
  std::string state_path;                      // its final state
  bool interrupted = false;                    // stopped (SweepOptions::stop): not a result
  bool resumed = false;                        // read back from its folder, or continued
};

struct SweepResult {
  std::vector<SweepPoint> up, down;  // each sorted by increasing velocity
  UmfFit umf;                        // from the decreasing branch
  double bed_weight_per_area = 0.0;  // Pa
  double wall_time = 0.0;            // s
  bool interrupted = false;          // a run was stopped: resume with SweepOptions::resume
};

// The sweep.json of a sweep's folder: what run_sweep(scene, options) would write there.
nlohmann::json sweep_identity(const Settings& scene, const SweepOptions& options);
// InputError (one line) for options run_sweep would refuse, and, with options.resume and a
// sweep.json in options.out_dir, unless run_sweep(scene, options) would resume that same sweep
// (naming what changed). Callers check before they touch the folder; run_sweep checks again.
void check_sweep_resume(const Settings& scene, const SweepOptions& options);
// OUT/sweep.json, read (InputError of one line when OUT holds no sweep).
nlohmann::json read_sweep_identity(const std::string& out_dir);

// 23 velocities from 0.5 to 3.2 m/s, denser around 1.4-2.2 m/s (the paper's 23 runs).
std::vector<double> default_sweep_velocities();
// The same list for `scene`'s particles and gas: scaled by the scene's Wen-Yu U_mf over the
// paper's (1.77 m/s; the paper's bed gets the paper's list), rounded to 0.01 m/s, and only
// velocities below 0.8 of a single sphere's terminal velocity (beyond it the gas carries
// particles out of the top; for spheres u_t is 8 or more times Wen-Yu's U_mf, so the list's top,
// 1.8 U_mf, stays below it and the cap only guards).
std::vector<double> default_sweep_velocities(const Settings& scene);
// The 8 velocities a decreasing branch alone is swept through for U_mf (SweepOptions::
// decreasing_only; the teaching study and the viewer's U_mf), m/s: 0.5, 0.9 (half the paper's
// U_mf of 1.8, the fixed bed), then 1.4 to 3.0 (U_mf near the middle, the plateau from 2.0); and
// the same list for `scene`, scaled as default_sweep_velocities(scene) is.
std::vector<double> decreasing_branch_velocities();
std::vector<double> decreasing_branch_velocities(const Settings& scene);
// A single sphere's terminal velocity in the scene's gas (m/s): its weight less buoyancy equals
// the Di Felice drag at porosity 1, C_d = (0.63 + 4.8 / sqrt(Re))^2 (model.md).
double terminal_velocity(const Settings& scene);

// The options of a decreasing branch alone (decreasing_only): VELOCITIES, RUN_TIME s each averaged
// from AVERAGING s, one run at a time, into OUT_DIR.
SweepOptions decreasing_branch_options(std::vector<double> velocities, double run_time,
                                       double averaging, std::string out_dir);
// The way down as U_mf's fit reads it, by increasing velocity: the decreasing branch's runs
// (finished or not) and last the highest finished increasing run, where the branch started.
std::vector<SweepPoint> way_down(const SweepResult& r);

// Throws InputError for bad options; failed runs are recorded, not thrown.
SweepResult run_sweep(const Settings& scene, const SweepOptions& options);

}  // namespace fluidbed
