#pragma once
// The outputs `run` and `reproduce` attach to a run in a folder (run/run_output.hpp): its
// pictures (frames, video, montage, VTK: output/frames.hpp) and its tracked particles with the
// figures drawn at its end (output/plots.hpp).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "output/frames.hpp"
#include "output/plots.hpp"
#include "run/run_output.hpp"

namespace fluidbed::app {

// Pictures at exact simulated times, drawn and written by FrameOutput's worker thread.
class PictureOutput : public RunOutput {
 public:
  PictureOutput(std::string dir, FrameOptions options);
  void start(const Simulation& sim, double until) override;
  void restore(const std::string& folder, const Simulation& sim, double until) override;
  void observe(const Simulation& sim) override { frames_->observe(sim); }
  void save(const std::string& folder) override { frames_->checkpoint(folder); }
  void finish(FinishedRun& run) override;
  void cleanup(const std::string& dir) override { remove_video_parts(dir); }
  // What the worker wrote and its cost (after finish).
  const FrameStats& stats() const { return stats_; }

 private:
  std::string dir_;
  FrameOptions options_;
  std::unique_ptr<FrameOutput> frames_;
  FrameStats stats_;
};

// The paths of chosen particles (every `interval` s of simulated time) and, at the run's end,
// its figures: dp, overlap, spectrum, bubbles, mixing and the trajectories (plot_run).
class PlotOutput : public RunOutput {
 public:
  // `choose` picks the tracked particles from the simulation as the run starts.
  PlotOutput(std::function<std::vector<int>(const Simulation&)> choose, double interval);
  void start(const Simulation& sim, double until) override;
  void restore(const std::string& folder, const Simulation& sim, double until) override;
  void observe(const Simulation& sim) override { tracks_->observe(sim); }
  void save(const std::string& folder) override { save_tracks(folder, *tracks_); }
  void finish(FinishedRun& run) override;
  // The figures written (after finish).
  const std::vector<std::string>& files() const { return files_; }

 private:
  std::function<std::vector<int>(const Simulation&)> choose_;
  double interval_;
  std::optional<TrajectoryRecorder> tracks_;
  std::vector<std::string> files_;
};

}  // namespace fluidbed::app
