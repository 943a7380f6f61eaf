#include "cli/view.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

#include "core/errors.hpp"
#include "core/steps.hpp"
#include "output/frames.hpp"
#include "render/gl_context.hpp"
#include "render/renderer.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "view/engine.hpp"
#include "view/script.hpp"
#include "view/script_runner.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

bool has_display() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (w && *w);
}

// The panel calls the initial-height colouring "mixing"; `run` calls it "height".
OutputArgs with_run_names(OutputArgs o) {
  if (o.colour == "mixing") o.colour = "height";
  return o;
}

// Without a window (ScriptTarget, view/script_runner.hpp): the gas velocity, the ideal case,
// screenshots and quit act at their simulated times; every other command has no effect.
class HeadlessScript : public ScriptTarget {
 public:
  HeadlessScript(ViewModel& model, const FrameOptions& fo) : model_(model), fo_(fo) {}

  void run_to(double t) override {
    target_step_ = steps_for(t, model_.sim().settings().time.dt);
  }
  bool busy() override { return model_.sim().steps() < target_step_; }
  bool stopped() const override { return quit_; }
  void unsupported(const ScriptLine& l) override {
    std::fprintf(stderr, "fluidbed view: headless: script line %d has no effect without a window\n",
                 l.line);
  }
  bool velocity(double u) override {
    model_.set_velocity(u);
    return true;
  }
  bool ideal(bool on) override {
    model_.set_ideal(on);
    return true;
  }
  bool screenshot(const std::string& file) override {
    if (!renderer_) {
      context_ = render::make_context("osmesa", fo_.width, fo_.height);
      renderer_ = std::make_unique<render::Renderer>(*context_, fo_.font);
    }
    Snapshot snap;
    take_snapshot(model_.sim(), snap);
    render::write_png(file, renderer_->render_frame(snap, fo_.look, fo_.width, fo_.height));
    std::printf("wrote %s\n", file.c_str());
    return true;
  }
  bool quit() override {
    quit_ = true;
    return true;
  }

 private:
  ViewModel& model_;
  const FrameOptions& fo_;
  std::int64_t target_step_ = 0;  // of the last `at T`
  bool quit_ = false;
  std::unique_ptr<render::GlContext> context_;
  std::unique_ptr<render::Renderer> renderer_;
};

// Without a window: the scene run headlessly with frames every --frame-interval (as `run
// --frames`), the script's gas velocity, ideal case and screenshots applied at their simulated
// times.
int view_headless(const Settings& s, const ViewArgs& a, const std::vector<ScriptLine>& script,
                  FrameOptions fo, const std::string& out) {
  ViewModel model(s);
  const double dt = s.time.dt;
  // The end: the script's quit (at the last time it named), else --until, else the scene's end.
  double until = a.run_like.until >= 0.0 ? a.run_like.until : s.time.end;
  {
    double t = 0.0;
    for (const ScriptLine& l : script) {
      if (l.at >= 0.0) t = std::max(t, l.at);
      if (l.kind == ScriptLine::Kind::quit) {
        until = t;
        break;
      }
    }
  }
  const std::int64_t last = steps_for(until, dt);
  fo.frames = true;
  FrameOutput pictures(out, fo, model.sim(), until);
  pictures.observe(model.sim());
  ScriptRunner runner(script);
  HeadlessScript target(model, fo);
  for (;;) {
    runner.advance(target);
    if (target.stopped() || model.sim().steps() >= last) break;
    model.sim().step();
    pictures.observe(model.sim());
  }
  const FrameStats st = pictures.finish();
  std::printf("wrote %d frames to %s/frames (t = 0 to %.4g s)\n", st.frames, out.c_str(),
              model.sim().time());
  return 0;
}

}  // namespace

int view_command(const ViewArgs& a) {
  const std::string scene =
      a.run_like.scene.empty() ? asset_dir() + "/scenes/teaching.toml" : a.run_like.scene;
  if (!std::filesystem::exists(scene)) throw InputError("cannot read the scene " + scene);
  Settings s = load_scene(scene, a.run_like.overrides);
  refuse_unsafe_scene(s);
  s.threads = a.run_like.threads;
  const std::vector<ScriptLine> script =
      a.script.empty() ? std::vector<ScriptLine>{} : load_view_script(a.script);
  const std::string out = a.out.empty() ? "out/view" : a.out;
  FrameOptions fo = frame_options(with_run_names(a.output), asset_dir());

  bool window = has_display();
  if (!window) {
    std::printf(
        "fluidbed view: no display (DISPLAY and WAYLAND_DISPLAY are unset): writing headless "
        "frames to %s/frames instead\n",
        out.c_str());
    std::fflush(stdout);
    return view_headless(s, a, script, fo, out);
  }

  ViewEngine::Options eo;
  eo.start_running = script.empty();  // a script starts paused and runs the bed itself
  ViewEngine engine(s, eo);
  ViewerOptions vo;
  vo.width = fo.width;
  vo.height = fo.height;
  vo.font = fo.font;
  vo.out_dir = out;
  vo.look = fo.look;
  vo.script = script;
  vo.max_fps = a.max_fps;
  std::unique_ptr<Viewer> viewer;
  try {
    viewer = std::make_unique<Viewer>(engine, vo);
  } catch (const std::runtime_error& e) {
    std::printf(
        "fluidbed view: cannot open a window (%s): writing headless frames to %s/frames "
        "instead\n",
        e.what(), out.c_str());
    std::fflush(stdout);
    engine.stop();
    return view_headless(s, a, script, fo, out);
  }
  engine.start();
  const int status = viewer->run();
  engine.stop();
  const ViewerStats st = viewer->stats();
  const EngineStatus es = engine.status();
  viewer.reset();
  std::printf("viewer: %d frames in %.2f s (%.1f frames/s, %.1f ms drawing each; %s)\n", st.frames,
              st.seconds, st.seconds > 0.0 ? st.frames / st.seconds : 0.0, st.draw_ms,
              st.gl_version.c_str());
  if (st.engine_seconds > 0.0)
    std::printf(
        "engine beside the window: %lld steps in %.2f s running (%.0f steps/s, %.4g sim s per "
        "wall s, %zu particles)\n",
        static_cast<long long>(st.engine_steps), st.engine_seconds,
        static_cast<double>(st.engine_steps) / st.engine_seconds,
        static_cast<double>(st.engine_steps) * s.time.dt / st.engine_seconds, es.particles);
  return status;
}

}  // namespace fluidbed::app
