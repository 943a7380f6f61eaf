#include "view/status_words.hpp"

#include <cstdio>

namespace fluidbed::app {

std::string run_state_words(const EngineStatus& st, bool script_runs_it) {
  if (!st.error.empty()) return "stopped: the simulation failed";
  char buf[96];
  if (st.run_until >= 0.0) {
    std::snprintf(buf, sizeof buf, "running to t = %.3f s%s", st.run_until,
                  script_runs_it ? " (script)" : "");
    return buf;
  }
  return st.stepping || st.running || script_runs_it ? "running" : "paused";
}

std::string speed_words(double r) {
  if (!(r > 0.0)) return "speed: not measured yet";
  char words[48], figure[64];
  if (r < 0.95)
    std::snprintf(words, sizeof words, "slow motion x %.1f", 1.0 / r);
  else if (r <= 1.05)
    std::snprintf(words, sizeof words, "real time");
  else
    std::snprintf(words, sizeof words, "fast motion x %.1f", r);
  std::snprintf(figure, sizeof figure, " (%.3g sim s per wall s)", r);
  return std::string(words) + figure;
}

std::string speed_for_a_class(double r) {
  if (!(r > 0.0)) return "";
  char buf[96];
  if (r < 0.95)
    std::snprintf(buf, sizeof buf, "slow motion: 1 s of the bed takes %.1f s here", 1.0 / r);
  else if (r <= 1.05)
    std::snprintf(buf, sizeof buf, "real time");
  else
    std::snprintf(buf, sizeof buf, "fast motion: 1 s of the bed takes %.2f s here", 1.0 / r);
  return buf;
}

}  // namespace fluidbed::app
