#pragma once
// One interpreter for view scripts (view/script.hpp), shared by the window (view/window.cpp) and
// the headless viewer (view/headless.cpp). The runner walks the lines in order: it first has the
// target run the engine to a line's `at T`, waits while the target is busy, then hands the
// command to the target as one call. A new command is a Kind and its words in view/script.*, a
// method of ScriptTarget here and one case in ScriptRunner::apply; each side then says whether it
// can carry it out.
#include <cstddef>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "view/script.hpp"

namespace fluidbed::app {

// What a script acts on. Each command returns true when this side carried it out; the defaults
// return false (the headless viewer has no window to zoom or record), and the runner then calls
// unsupported() with the line.
class ScriptTarget {
 public:
  virtual ~ScriptTarget() = default;

  // Timing. run_to: start the engine towards the step nearest simulated time t (s), to stop
  // there. busy: the next line must wait (the engine on its way, a wait, a screenshot not yet
  // written). stopped: the script is over (quit, or a command that failed).
  virtual void run_to(double t) = 0;
  virtual bool busy() = 0;
  virtual bool stopped() const = 0;
  virtual void unsupported(const ScriptLine& line) = 0;

  // The scene's measured minimum fluidization velocity (m/s; 0: not measured): presets and
  // `velocity F umf` are carried out as velocity(F * umf()).
  virtual double umf() const { return 0.0; }

  // The bed's simulated time and particle step (s; a step of 0: not known): a line's `at T`
  // that the bed has already passed (an earlier wait or steps ran it on) is carried out at once
  // and said through note().
  virtual double sim_time() const { return 0.0; }
  virtual double sim_step() const { return 0.0; }
  // A line of the script's log (the default: standard error).
  virtual void note(const std::string& text);

  // The commands, as view/script.hpp lists them.
  virtual bool velocity(double /*m_per_s*/) { return false; }
  virtual bool ideal(bool /*on*/) { return false; }
  virtual bool stiffness(double /*N_per_m, 0: the scene's*/) { return false; }
  virtual bool particles(double /*diameter m, 0: the scene's*/, double /*density kg/m^3*/) {
    return false;
  }
  virtual bool settle(double /*simulated_seconds*/) { return false; }
  virtual bool average(double /*simulated_seconds*/) { return false; }
  virtual bool save_curve(const std::string& /*file .csv or .png*/) { return false; }
  virtual bool caption(const std::string& /*text, empty: none*/) { return false; }
  virtual bool run_switch(bool /*running: run, or pause*/) { return false; }
  virtual bool step(double /*count*/) { return false; }
  virtual bool reset() { return false; }
  virtual bool wait(double /*wall_seconds*/) { return false; }
  virtual bool colour(const std::string& /*mode*/) { return false; }
  virtual bool gas_arrows(bool /*on*/) { return false; }
  virtual bool particle_arrows(bool /*on*/) { return false; }
  virtual bool porosity(bool /*on*/) { return false; }
  virtual bool bubbles(bool /*on: outlines of bubbles and jet cavities*/) { return false; }
  virtual bool track(long /*id, -1: off*/, int /*line*/) { return false; }
  virtual bool zoom(double /*factor*/) { return false; }
  virtual bool screenshot(const std::string& /*file*/) { return false; }
  virtual bool record(const std::string& /*file_or_folder*/) { return false; }
  virtual bool record_stop() { return false; }
  virtual bool quit() { return false; }
};

class ScriptRunner {
 public:
  explicit ScriptRunner(std::vector<ScriptLine> lines) : lines_(std::move(lines)) {}

  // Carries out lines until one must wait (the target is busy or its `at T` is not reached),
  // the target stops, or the lines run out.
  void advance(ScriptTarget& target);
  bool empty() const { return lines_.empty(); }
  bool at_end() const { return next_ >= lines_.size(); }  // every line carried out

  // The one place a line becomes a call.
  static void apply(const ScriptLine& line, ScriptTarget& target);

 private:
  std::vector<ScriptLine> lines_;
  std::size_t next_ = 0;
  bool at_asked_ = false;  // the current line's run_to was called
};

}  // namespace fluidbed::app
