#include "cli/interrupt.hpp"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>

#include "core/errors.hpp"

namespace fluidbed::app {
namespace {

// A signal handler can only reach state of static duration; a lock-free atomic is safe to set
// from it.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_signal(int s) { g_signal.store(s, std::memory_order_relaxed); }

struct sigaction g_old_int, g_old_term;

}  // namespace

InterruptGuard::InterruptGuard() {
  g_signal.store(0);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
}

int InterruptGuard::received() { return g_signal.load(std::memory_order_relaxed); }

const char* InterruptGuard::name(int signal) {
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
}

void say_interrupted(const std::string& resume_command) {
  std::fprintf(stderr, "interrupted (%s); resume with: %s\n",
               InterruptGuard::name(InterruptGuard::received()), resume_command.c_str());
}

void check_resume_out(const std::string& out, const std::string& resume, const std::string& head,
                      const std::string& what) {
  namespace fs = std::filesystem;
  if (!out.empty() && fs::absolute(out).lexically_normal() != fs::absolute(resume).lexically_normal())
    throw InputError(head + "--out " + out + " is not the " + what + "'s folder");
}

void check_resume_only(bool options_given, const std::string& out, const std::string& resume,
                       const std::string& what, const std::string& takes) {
  const std::string head = "cannot resume " + resume + ": ";
  if (options_given)
    throw InputError(head + "a resumed " + what + " takes " + takes +
                     " (give only --resume DIR and, if wanted, --threads)");
  check_resume_out(out, resume, head, what);
}

}  // namespace fluidbed::app
