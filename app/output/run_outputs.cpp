#include "output/run_outputs.hpp"

namespace fluidbed::app {

PictureOutput::PictureOutput(std::string dir, FrameOptions options)
    : dir_(std::move(dir)), options_(std::move(options)) {}

void PictureOutput::start(const Simulation& sim, double until) {
  frames_ = std::make_unique<FrameOutput>(dir_, options_, sim, until);
  frames_->observe(sim);  // the starting state, when it is an output time
}

void PictureOutput::restore(const std::string& folder, const Simulation& sim, double until) {
  frames_ = std::make_unique<FrameOutput>(dir_, options_, sim, until, folder);
}

void PictureOutput::finish(FinishedRun&) {
  stats_ = frames_->finish();
}

PlotOutput::PlotOutput(std::function<std::vector<int>(const Simulation&)> choose, double interval)
    : choose_(std::move(choose)), interval_(interval) {}

void PlotOutput::start(const Simulation& sim, double) {
  tracks_.emplace(choose_(sim), interval_, sim.settings().time.dt);
}

void PlotOutput::restore(const std::string& folder, const Simulation& sim, double until) {
  start(sim, until);
  restore_tracks(folder, *tracks_, sim.particle_count());
}

void PlotOutput::finish(FinishedRun& run) {
  const Settings& s = run.sim.settings();
  files_ = plot_run(run.dir, run.result, tracks_->tracks(), s.domain.width, s.domain.height,
                    run.sim.has_gas());
}

}  // namespace fluidbed::app
