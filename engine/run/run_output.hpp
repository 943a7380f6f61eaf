#pragma once
// What a run records along the way besides its timeseries and summary (pictures, tracked
// particles, probes, ...): one small interface through which an output attaches to a run in a
// folder (run/run_folder.hpp). The run calls, in order:
//   start(sim, until)            a new run, before its first step (the output may take the
//                                starting state now, when that is one of its times);
//   restore(folder, sim, until)  instead of start, for a run resumed from the checkpoint in
//                                `folder`: the output as save() left it there;
//   observe(sim)                 after every step (read only; must not change the run);
//   save(folder)                 into a checkpoint being written, between two steps;
//   finish(run)                  once the run finished, before its own files and its finished
//                                marker are written: the output's files, its figures for the
//                                marker's `result`;
//   cleanup(dir)                 after the checkpoint, which may name the output's parts, is gone.
// Adding an output to every verb that runs into a folder is one class and one line where the
// verb attaches it (RunJob::outputs).
#include <nlohmann/json.hpp>
#include <string>

#include "run/run_loop.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {

// A finished run as its outputs see it.
struct FinishedRun {
  const std::string& dir;         // the run's folder
  const Simulation& sim;          // at its end
  const RunResult& result;        // rows, summary, spectrum, bubble rows
  nlohmann::json& result_record;  // the finished marker's `result` object (status.json)
};

class RunOutput {
 public:
  virtual ~RunOutput() = default;
  virtual void start(const Simulation& sim, double until) = 0;
  virtual void restore(const std::string& folder, const Simulation& sim, double until) = 0;
  virtual void observe(const Simulation& sim) = 0;
  virtual void save(const std::string& folder) = 0;
  virtual void finish(FinishedRun& run) = 0;
  virtual void cleanup(const std::string& /*dir*/) {}
};

}  // namespace fluidbed
