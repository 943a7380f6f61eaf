#pragma once
// The viewer's main thread: a GLFW window with Dear ImGui. Each frame it polls events, takes the
// newest snapshot the engine published, draws the bed (renderer) and the panel (ImGui), and sends
// the panel's edits to the engine as commands. It never waits for the engine, nor the engine for it
// (a script's `at T` is the one exception: the engine stops at T, the window keeps drawing).
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/gl_context.hpp"
#include "render/picking.hpp"
#include "render/render_settings.hpp"
#include "render/renderer.hpp"
#include "render/video_writer.hpp"
#include "view/engine.hpp"
#include "view/script.hpp"
#include "view/script_runner.hpp"

namespace fluidbed::app {

struct ViewerOptions {
  int width = 1360, height = 800;  // px, the window
  std::string font;                // TrueType file for the renderer and the panel
  std::string out_dir;             // screenshots and recordings
  render::RenderSettings look;
  std::vector<ScriptLine> script;
  // Frames per second the window draws at most (0: as fast as it can). The eye needs no more
  // than about 30; every frame drawn beyond that takes a core from the engine (under Xvfb,
  // llvmpipe drew 80 a second and the engine on two threads ran slower than on one).
  double max_fps = 30.0;
};

// What the window measured, printed at the end (the viewer's benchmark).
struct ViewerStats {
  int frames = 0;
  double seconds = 0.0;           // wall time with the window open
  double draw_ms = 0.0;           // mean time per frame spent drawing (scene + panel)
  std::int64_t engine_steps = 0;  // steps while the window was open
  double engine_seconds = 0.0;    // wall time the engine was running while the window was open
  std::string gl_version;
};

// The window carries out every script command (ScriptTarget, view/script_runner.hpp).
class Viewer : private ScriptTarget {
 public:
  // Opens the window (throws std::runtime_error when it cannot) and sets up ImGui.
  Viewer(ViewEngine& engine, ViewerOptions options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Runs until the window closes or the script quits; returns the exit status.
  int run();
  const ViewerStats& stats() const { return stats_; }

 private:
  void frame();
  void take_newest();
  void draw_scene();
  void handle_scene_input();
  void draw_overlays();
  void draw_panel();
  void draw_plots();
  void draw_particle_info(std::size_t id, bool tooltip);
  void step_script();
  void capture_if_requested();
  void start_recording(const std::string& target);
  void stop_recording();
  void post(const ViewCommand& c);
  void toggle_run();
  void cycle_colour();
  std::string next_name(const std::string& stem, const std::string& ext);

  // ScriptTarget: the script's commands.
  void run_to(double t) override;
  bool busy() override;
  bool stopped() const override { return quit_; }
  void unsupported(const ScriptLine& line) override;
  bool velocity(double m_per_s) override;
  bool ideal(bool on) override;
  bool run_switch(bool running) override;
  bool step(double count) override;
  bool reset() override;
  bool wait(double wall_seconds) override;
  bool colour(const std::string& mode) override;
  bool gas_arrows(bool on) override;
  bool particle_arrows(bool on) override;
  bool porosity(bool on) override;
  bool bubbles(bool on) override;
  bool track(long id, int line) override;
  bool zoom(double factor) override;
  bool screenshot(const std::string& file) override;
  bool record(const std::string& target) override;
  bool record_stop() override;
  bool quit() override;

  ViewEngine& engine_;
  ViewerOptions opt_;
  std::unique_ptr<render::GlContext> context_;
  std::unique_ptr<render::Renderer> renderer_;
  bool imgui_glfw_ = false, imgui_gl_ = false;

  // The newest state and what the panel shows.
  std::shared_ptr<const Snapshot> snap_;
  std::uint64_t snap_seq_ = 0;
  EngineStatus status_;
  render::RenderSettings look_;
  render::ViewTransform view_;
  float panel_width_ = 380.0f;
  render::Rect area_;              // the scene in window pixels
  int frame_w_ = 0, frame_h_ = 0;  // the drawn frame (px)
  render::FrameLayout layout_;
  float velocity_ = 0.0f;  // the slider (m/s)
  float velocity_top_ = 0.0f;  // its range's top (m/s), fixed at the first frame with gas
  bool ideal_ = false;
  std::optional<std::size_t> hovered_;
  bool mouse_moved_ = false;
  long tracked_ = -1;
  std::vector<std::pair<double, double>> trajectory_;  // m, of the tracked particle
  std::int64_t trajectory_step_ = -1;

  // Plots (the last few thousand samples).
  std::uint64_t plot_generation_ = 0;
  std::vector<float> plot_t_, plot_dp_, plot_overlap_;

  // Screenshots and recording.
  std::vector<std::string> screenshot_requests_;
  int settle_frames_ = 0;  // frames to draw before a scripted screenshot
  std::unique_ptr<render::VideoWriter> video_;
  std::string record_dir_;  // PNG frames
  std::string record_target_;
  int record_frames_ = 0;
  int record_frames_w_ = 0, record_frames_h_ = 0;  // px, an MP4's fixed size (even)
  std::chrono::steady_clock::time_point record_t0_;
  bool record_mp4_ = true;
  int counter_ = 0;
  std::string message_;  // the last thing written, or a problem

  // The script.
  ScriptRunner script_;
  bool script_waiting_engine_ = false;
  bool script_finished_ = false;
  std::optional<std::chrono::steady_clock::time_point> script_wait_until_;
  bool script_wants_running_ = true;
  bool quit_ = false;
  int exit_status_ = 0;

  // Measurements.
  std::chrono::steady_clock::time_point t0_, last_status_t_;
  std::int64_t last_status_steps_ = 0;
  bool last_running_ = false;
  double draw_seconds_ = 0.0;
  ViewerStats stats_;
};

}  // namespace fluidbed::app
