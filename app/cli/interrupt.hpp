#pragma once
// SIGINT and SIGTERM as a request to stop at the end of the current step (`fluidbed run`): the
// handler only sets a flag, which the run loop asks after every step (RunOptions::stop).
#include <string>

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

// What an interrupted command prints (stderr, one line): "interrupted (SIGTERM); resume with:
// RESUME_COMMAND".
void say_interrupted(const std::string& resume_command);

// `--out OUT` beside `--resume DIR`: InputError ("HEAD--out OUT is not the WHAT's folder") unless
// OUT is empty or names DIR.
void check_resume_out(const std::string& out, const std::string& resume, const std::string& head,
                      const std::string& what);

// `--resume DIR` of a WHAT that keeps how it was started in DIR: InputError ("cannot resume DIR: a
// resumed WHAT takes TAKES (give only --resume DIR and, if wanted, --threads)") when other options
// were given, then check_resume_out.
void check_resume_only(bool options_given, const std::string& out, const std::string& resume,
                       const std::string& what, const std::string& takes);

}  // namespace fluidbed::app
