#include "cli/view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "core/errors.hpp"
#include "core/steps.hpp"
#include "output/frames.hpp"
#include "render/colour_by.hpp"
#include "run/umf_estimate.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "view/engine.hpp"
#include "view/headless.hpp"
#include "view/script.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

bool has_display() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (w && *w);
}

// The viewer's colour words are taken on the command line too ("mixing": `run`'s "height").
OutputArgs with_run_names(OutputArgs o) {
  if (const auto c = render::find_colour_by(o.colour)) o.colour = render::to_string(*c);
  return o;
}

std::string lessons_dir() {
  return asset_dir() + "/lessons";
}

// The lesson's file; InputError naming the lessons there are for a name that is not one.
std::string lesson_file(const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path file = fs::path(lessons_dir()) / (name + ".txt");
  if (name.find('/') == std::string::npos && fs::exists(file)) return file.string();
  std::string known;
  for (const auto& [n, title] : list_lessons()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("no lesson '" + name + "' (known: " + (known.empty() ? "none" : known) +
                   "; `fluidbed view --list-lessons`)");
}

// A lesson's `scene NAME`: a path as given, else relative to the lesson, else a shipped scene.
std::string resolve_scene(const std::string& name, const std::string& script_path) {
  namespace fs = std::filesystem;
  for (const fs::path& p : {fs::path(name), fs::path(script_path).parent_path() / name,
                            fs::path(asset_dir()) / "scenes" / name})
    if (fs::exists(p)) return p.string();
  throw InputError("the scene " + name + " named in " + script_path + " was not found");
}

// Stiffness lines are checked against the scene before anything runs (a step too long for a
// stiffer contact is bad input, status 2, not a failure half-way through a lesson).
void check_script_against(const ViewScript& script, const Settings& s, const std::string& origin) {
  for (const ScriptLine& l : script.lines) {
    if (l.kind == ScriptLine::Kind::stiffness && l.number > 0.0) {
      try {
        (void)with_contact(s, false, l.number);
      } catch (const InputError& e) {
        throw InputError(origin + " line " + std::to_string(l.line) + ": " + e.what());
      }
    }
    const bool needs_gas = l.kind == ScriptLine::Kind::preset ||
                           (l.kind == ScriptLine::Kind::velocity && l.text == "umf");
    if (needs_gas && !s.gas.enabled)
      throw InputError(origin + " line " + std::to_string(l.line) +
                       ": presets and velocities in U_mf need a scene with gas");
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> list_lessons() {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, std::string>> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(lessons_dir(), ec)) {
    if (e.path().extension() != ".txt") continue;
    std::ifstream in(e.path());
    std::string line, title;
    while (std::getline(in, line))
      if (line.rfind("# ", 0) == 0) {
        title = line.substr(2);
        break;
      }
    out.emplace_back(e.path().stem().string(), title);
  }
  std::sort(out.begin(), out.end());
  return out;
}

int view_command(const ViewArgs& a) {
  if (a.list_lessons) {
    const auto lessons = list_lessons();
    if (lessons.empty()) throw InputError("no lessons in " + lessons_dir());
    for (const auto& [name, title] : lessons)
      std::printf("%-20s %s\n", name.c_str(), title.c_str());
    return 0;
  }
  if (!a.script.empty() && !a.lesson.empty())
    throw InputError("view takes --script FILE or --lesson NAME, not both");
  const std::string script_path = a.lesson.empty() ? a.script : lesson_file(a.lesson);
  ViewScript script = script_path.empty() ? ViewScript{} : load_view_script(script_path);
  const std::string out = a.out.empty() ? "out/view" : a.out;
  if (!a.lesson.empty()) {
    // A lesson's files (screenshots, saved curves, recordings) go into the output folder.
    for (ScriptLine& l : script.lines) {
      const bool file = l.kind == ScriptLine::Kind::screenshot ||
                        l.kind == ScriptLine::Kind::record || l.kind == ScriptLine::Kind::curve;
      if (file && std::filesystem::path(l.text).is_relative())
        l.text = (std::filesystem::path(out) / l.text).string();
    }
  }
  std::string scene = a.run_like.scene;
  if (scene.empty() && !script.scene.empty()) scene = resolve_scene(script.scene, script_path);
  if (scene.empty()) scene = asset_dir() + "/scenes/teaching.toml";
  if (!std::filesystem::exists(scene)) throw InputError("cannot read the scene " + scene);
  Settings s = load_scene(scene, a.run_like.overrides);
  refuse_unsafe_scene(s);
  s.threads = a.run_like.threads;
  std::optional<Settings> beside;
  if (!a.beside.empty()) {
    if (!std::filesystem::exists(a.beside)) throw InputError("cannot read the scene " + a.beside);
    beside = load_scene(a.beside, a.run_like.overrides);
    refuse_unsafe_scene(*beside);
    beside->threads = a.run_like.threads;
  }
  check_script_against(script, s, script_path);
  FrameOptions fo = frame_options(with_run_names(a.output), asset_dir(), s);
  // A lesson's video in slow motion (x 2 at 25 frames per second), time to read its captions.
  if (!a.lesson.empty() && !a.frame_interval_given) fo.interval = 0.02;
  const bool window = has_display();

  // The scene's own U_mf (the slider's scale and ticks, the presets): measured once, cached.
  UmfEstimate umf;
  if (a.umf_only && !s.gas.enabled)
    throw InputError("the scene has no gas: it has no minimum fluidization velocity");
  if (s.gas.enabled && (window || script.needs_umf() || a.umf_only)) {
    try {
      umf = estimate_umf(
          s,
          [](const std::string& line) {
            std::printf("fluidbed view: %s\n", line.c_str());
            std::fflush(stdout);
          },
          asset_dir() + "/umf");
    } catch (const std::exception& e) {
      if (script.needs_umf() || a.umf_only) throw;  // the script's presets cannot be carried out
      std::printf("fluidbed view: no U_mf for this scene (%s): no presets\n", e.what());
    }
  }
  if (umf.umf > 0.0) {
    std::printf(
        "fluidbed view: U_mf = %.3f m/s (%s; %s)\n", umf.umf, umf.method().c_str(),
        umf.from_cache ? ("cached: " + umf.cache_file).c_str()
                       : (std::to_string(umf.evaluations) + " runs").c_str());
  }
  if (a.umf_only) return 0;

  HeadlessView hv;
  hv.frames = fo;
  hv.out = out;
  hv.until = a.run_like.until;
  hv.umf = umf;
  hv.umf_shipped = asset_dir() + "/umf";
  hv.frames.frames = true;
  // A lesson is made into a teaching video; a plain scene with --video too.
  hv.frames.video = fo.video || !a.lesson.empty();
  if (!window) {
    std::printf(
        "fluidbed view: no display (DISPLAY and WAYLAND_DISPLAY are unset): writing headless "
        "frames to %s/frames instead\n",
        out.c_str());
    if (a.present)
      std::printf(
          "fluidbed view: --present is the window's; headless frames of a bed with gas "
          "already show it beside the live Fig. 6\n");
    if (beside)
      std::printf("fluidbed view: --beside is the window's; the headless frames show %s only\n",
                  scene.c_str());
    std::fflush(stdout);
    return view_headless(s, script, hv);
  }

  ViewEngine::Options eo;
  eo.umf = umf;
  eo.umf_shipped = asset_dir() + "/umf";
  eo.start_running = script.lines.empty();  // a script starts paused and runs the bed itself
  ViewEngine engine(s, eo);
  ViewerOptions vo;
  vo.width = fo.width;
  vo.height = fo.height;
  vo.font = fo.font;
  vo.out_dir = out;
  vo.look = fo.look;
  vo.script = script.lines;
  vo.max_fps = a.max_fps;
  vo.umf = umf.umf;
  vo.umf_cached = umf.from_cache;
  vo.umf_method = umf.method();
  vo.umf_method_short = umf.method_short();
  vo.scene_velocity = s.gas.enabled ? s.inlet.superficial_velocity : 0.0;
  vo.dt = s.time.dt;
  vo.lesson = !a.lesson.empty();
  vo.present = a.present;
  vo.scene = s;
  std::unique_ptr<ViewEngine> beside_engine;
  if (beside) {
    beside_engine = std::make_unique<ViewEngine>(*beside, eo);
    vo.beside = beside_engine.get();
    vo.beside_name = beside->scene.name;
  }
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
    return view_headless(s, script, hv);
  }
  engine.start();
  if (beside_engine) beside_engine->start();
  const int status = viewer->run();
  engine.stop();
  if (beside_engine) beside_engine->stop();
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
  std::printf("viewer: stopped at t = %.6f s, step %lld, U = %.4f m/s\n", es.time,
              static_cast<long long>(es.steps), es.superficial_velocity);
  if (s.gas.enabled) std::printf("viewer: %s\n", describe_curve(es.curve).c_str());
  if (beside_engine) {
    const EngineStatus bs = beside_engine->status();
    std::printf("beside: stopped at t = %.6f s, step %lld, U = %.4f m/s\n", bs.time,
                static_cast<long long>(bs.steps), bs.superficial_velocity);
  }
  return status;
}

}  // namespace fluidbed::app
