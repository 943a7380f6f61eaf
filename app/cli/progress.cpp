#include "cli/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace fluidbed::app {

ProgressFn progress_printer(double until) {
  if (isatty(STDERR_FILENO) == 0) return {};
  return [until](const Simulation& sim, double wall) {
    const double t = sim.time();
    const double steps = static_cast<double>(sim.steps());
    std::fprintf(stderr,
                 "\r  t = %.4f / %.4f s   %.3g wall s per sim s   %.3g particle-steps/s   ", t,
                 until, t > 0.0 ? wall / t : 0.0,
                 wall > 0.0 ? steps * static_cast<double>(sim.particle_count()) / wall : 0.0);
    std::fflush(stderr);
  };
}

void end_progress(const ProgressFn& progress) {
  if (progress) std::fprintf(stderr, "\n");
}

RunResult run_with_progress(Simulation& sim, double until) {
  RunOptions opt;
  opt.until = until;
  opt.progress = progress_printer(until);
  RunResult r = run_simulation(sim, opt);
  end_progress(opt.progress);
  return r;
}

}  // namespace fluidbed::app
