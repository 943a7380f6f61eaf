#pragma once
// SIGINT and SIGTERM as a request to stop at the end of the current step (`fluidbed run`): the
// handler only sets a flag, which the run loop asks after every step (RunOptions::stop).
namespace fluidbed::app {

// Installs the handlers for the life of the object and puts back the previous ones after.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  // The signal received (SIGINT or SIGTERM), or 0.
  static int received();
  static const char* name(int signal);
};

}  // namespace fluidbed::app
