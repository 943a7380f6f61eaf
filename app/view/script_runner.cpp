#include "view/script_runner.hpp"

#include <cmath>

#include "core/steps.hpp"
#include "core/text_format.hpp"
#include "view/presets.hpp"

namespace fluidbed::app {

void ScriptTarget::note(const std::string& text) {
  std::fprintf(stderr, "fluidbed view: %s\n", text.c_str());
}

void ScriptRunner::advance(ScriptTarget& target) {
  while (!target.stopped() && next_ < lines_.size()) {
    if (target.busy()) return;
    const ScriptLine& l = lines_[next_];
    if (l.at >= 0.0 && !at_asked_) {
      at_asked_ = true;
      // Behind its time: the step nearest T is past (by more than half a step).
      if (const double dt = target.sim_step(); dt > 0.0) {
        const double nearest = static_cast<double>(steps_for(l.at, dt)) * dt;
        if (target.sim_time() > nearest + 0.5 * dt)
          target.note("script line " + std::to_string(l.line) + ": `at " +
                      format_number("%g", l.at) + "` came late, at t = " +
                      format_number("%.4g s", target.sim_time()) +
                      ": an earlier line (a wait, steps) ran the bed past it");
      }
      target.run_to(l.at);
      continue;  // busy until the engine is there
    }
    at_asked_ = false;
    ++next_;
    apply(l, target);
  }
}

void ScriptRunner::apply(const ScriptLine& l, ScriptTarget& t) {
  using K = ScriptLine::Kind;
  const bool on = l.number != 0.0;
  bool done = false;
  switch (l.kind) {
    case K::velocity:
      if (l.text != "umf")
        done = t.velocity(l.number);
      else if (t.umf() > 0.0)
        done = t.velocity(l.number * t.umf());
      break;
    case K::preset:
      if (const Preset* p = find_preset(l.text); p && t.umf() > 0.0)
        done = t.velocity(p->umf_multiple * t.umf());
      break;
    // clang-format off
    case K::stiffness: done = t.stiffness(l.number); break;
    case K::particles: done = t.particles(l.number, l.density); break;
    case K::settle: done = t.settle(l.number); break;
    case K::average: done = t.average(l.number); break;
    case K::curve: done = t.save_curve(l.text); break;
    case K::caption: done = t.caption(l.text); break;
    case K::ideal: done = t.ideal(on); break;
    case K::run: done = t.run_switch(true); break;
    case K::pause: done = t.run_switch(false); break;
    case K::step: done = t.step(l.number); break;
    case K::reset: done = t.reset(); break;
    case K::wait: done = t.wait(l.number); break;
    case K::colour: done = t.colour(l.text); break;
    case K::gas_arrows: done = t.gas_arrows(on); break;
    case K::particle_arrows: done = t.particle_arrows(on); break;
    case K::porosity: done = t.porosity(on); break;
    case K::bubbles: done = t.bubbles(on); break;
    case K::track: done = t.track(static_cast<long>(l.number), l.line); break;
    case K::zoom: done = t.zoom(l.number); break;
    case K::screenshot: done = t.screenshot(l.text); break;
    case K::record: done = t.record(l.text); break;
    case K::record_stop: done = t.record_stop(); break;
    case K::quit: done = t.quit(); break;
      // clang-format on
  }
  if (!done) t.unsupported(l);
}

}  // namespace fluidbed::app
