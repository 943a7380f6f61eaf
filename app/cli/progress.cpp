#include "cli/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <utility>

namespace fluidbed::app {
namespace {

void print_progress(const Simulation& sim, double wall, double until) {
  const double t = sim.time();
  const double steps = static_cast<double>(sim.steps());
  std::fprintf(stderr, "\r  t = %.4f / %.4f s   %.3g wall s per sim s   %.3g particle-steps/s   ",
               t, until, t > 0.0 ? wall / t : 0.0,
               wall > 0.0 ? steps * static_cast<double>(sim.particle_count()) / wall : 0.0);
  std::fflush(stderr);
}

}  // namespace

RunResult run_with_progress(Simulation& sim, double until,
                            std::function<void(const Simulation&)> on_step, bool bubbles,
                            std::function<void(const TimeseriesRow&)> on_row,
                            std::function<bool()> stop) {
  RunOptions opt;
  opt.on_row = std::move(on_row);
  opt.stop = std::move(stop);
  opt.until = until;
  opt.bubbles = bubbles;
  opt.on_step = std::move(on_step);
  return run_with_progress(sim, until, std::move(opt));
}

RunResult run_with_progress(Simulation& sim, double until, RunOptions opt) {
  opt.until = until;
  const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal) opt.progress = [until](const Simulation& s, double w) { print_progress(s, w, until); };
  RunResult r = run_simulation(sim, opt);
  if (terminal) std::fprintf(stderr, "\n");
  return r;
}

}  // namespace fluidbed::app
