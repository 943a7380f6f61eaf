#pragma once
// The viewer's main thread: a GLFW window with Dear ImGui. Each frame it polls events, takes the
// newest snapshot the engine published, draws the bed (renderer) and the panel (ImGui), and sends
// the panel's edits to the engine as commands. It never waits for the engine, nor the engine for it
// (a script's `at T` is the one exception: the engine stops at T, the window keeps drawing).
// window.cpp: the frame, input, zoom and the script; saved_files.cpp: saved files and what the
// panel says of them; panel.cpp: the panel;
// panel_plots.cpp: its plots (dp, overlap, the live Fig. 6); overlays.cpp: rings, paths and the
// bubble under the pointer. Screenshots and recordings of the window: view/capture.hpp.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/gl_context.hpp"
#include "render/picking.hpp"
#include "render/render_settings.hpp"
#include "render/renderer.hpp"
#include "view/capture.hpp"
#include "view/engine.hpp"
#include "view/panel_layout.hpp"
#include "view/script.hpp"
#include "view/script_runner.hpp"

struct ImFont;
struct ImVec2;

namespace fluidbed::app {

struct ViewerOptions {
  int width = 1280, height = 720;  // px, the window
  std::string font;                // TrueType file for the renderer and the panel
  std::string out_dir;             // screenshots, recordings, saved curves
  render::RenderSettings look;
  std::vector<ScriptLine> script;
  // Frames per second the window draws at most (0: as fast as it can). The eye needs no more
  // than about 30; every frame drawn beyond that takes a core from the engine (under Xvfb,
  // llvmpipe drew 80 a second and the engine on two threads ran slower than on one).
  double max_fps = 30.0;
  // The scene's measured minimum fluidization velocity (m/s; 0: not measured, no presets), and
  // whether it came from the cache.
  double umf = 0.0;
  bool umf_cached = false;
  std::string umf_method, umf_method_short;  // how it was measured (UmfEstimate)
  double scene_velocity = 0.0;  // m/s, the scene's own (a tick on the slider)
  double dt = 0.0;              // s, the scene's particle step (a script's `at T` that came late)
  // The script is a lesson: its `quit` ends the lesson but leaves the window open on its last
  // picture and curve until the teacher closes it (a --script quits).
  bool lesson = false;
  // Open in the presenter mode (`view --present`; the `p` key switches it): view/presenter.cpp.
  bool present = false;
  // A second bed beside the first (`view A --beside B`; its engine is the caller's, running), and
  // what to call it; the scene itself, for the panel's ideal twin.
  ViewEngine* beside = nullptr;
  std::string beside_name;
  Settings scene;
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
  ~Viewer() override;
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Runs until the window closes or the script quits; returns the exit status.
  int run();
  const ViewerStats& stats() const { return stats_; }

  // GLFW's key callback (installed before ImGui's, which calls it first): presses are queued, so
  // that a tap shorter than a frame still acts.
  void key_event(int key, int action);

 private:
  void frame();
  void take_newest();
  void place_frame();
  void draw_scene();
  void handle_scene_input();
  void handle_keys();
  void follow_tracked();
  // overlays.cpp
  void draw_overlays();
  void draw_hover_tooltip(const std::optional<std::size_t>& particle, const Bubble* bubble);
  // panel.cpp, panel_plots.cpp
  void draw_panel();
  void draw_top_block();
  void draw_messages(bool for_a_class = false);
  void draw_gas_section();
  void draw_curve_section();
  void draw_bed_section();
  void draw_look_section();
  void draw_particles_section();
  void draw_plots();
  void draw_curve_plot(float height, bool for_a_class = false);
  void velocity_slider(const char* format);
  void fig6_button(const ImVec2& size);
  ImFont* font_of(float size) const;  // the largest loaded font not above `size` px
  // presenter.cpp: the presenter mode's right-hand side and its words in the bed.
  void draw_presenter();
  void draw_bed_labels();
  void draw_particle_info(std::size_t id, bool tooltip);
  void note_widget(const char* name, const std::string& value = "");
  // saved_files.cpp
  void write_widgets();
  void save_curve_file(const std::string& path);
  void write_output(const std::string& path, const std::function<void()>& write);
  std::string next_name(const std::string& stem, const std::string& ext);
  // window.cpp
  void step_script();
  void start_recording(const std::string& target);  // of the window at its size now
  void post(const ViewCommand& c);
  void toggle_run();
  void cycle_colour();
  void set_velocity(double u);
  bool script_runs_the_bed() const;  // from one `at T` to the next
  bool bed_is_running() const;       // what Run / Pause shows: stepping, or a script running it
  // Frame pixels (the renderer's frame, in the bed area) <-> window pixels.
  float to_window_x(double fx) const;
  float to_window_y(double fy) const;

  // The bed beside (beside.cpp): the ideal twin on or off, the beside bed's state, its frame.
  void toggle_twin();
  void take_beside();
  void draw_beside_frame();
  void draw_beside_section();

  // ScriptTarget: the script's commands.
  void run_to(double t) override;
  bool busy() override;
  bool stopped() const override { return quit_ || lesson_over_; }
  double sim_time() const override { return status_.time; }
  double sim_step() const override { return opt_.dt; }
  void unsupported(const ScriptLine& line) override;
  double umf() const override { return opt_.umf; }
  bool velocity(double m_per_s) override;
  bool ideal(bool on) override;
  bool stiffness(double k) override;
  bool particles(double diameter, double density) override;
  bool settle(double s) override;
  bool average(double s) override;
  bool save_curve(const std::string& file) override;
  bool caption(const std::string& text) override;
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
  std::vector<std::pair<float, ImFont*>> fonts_;  // the panel's font at a few pixel sizes

  // The newest state and what the panel shows.
  std::shared_ptr<const Snapshot> snap_;
  std::uint64_t snap_seq_ = 0;
  EngineStatus status_;
  render::RenderSettings look_;
  PanelLayout panel_;
  bool present_ = false;  // the presenter mode (view/presenter.cpp)
  PresenterLayout presenter_;
  render::Rect area_;              // the bed area in window pixels
  float fb_scale_ = 1.0f;          // framebuffer pixels per window pixel
  int frame_w_ = 0, frame_h_ = 0;  // the drawn frame (framebuffer px)
  render::FrameLayout layout_;     // of the frame, zoom included
  float velocity_ = 0.0f;          // the slider (m/s)
  float velocity_top_ = 0.0f;      // its range's top (m/s), fixed when the window opens
  bool typed_velocity_ = false;    // a velocity typed into the slider, applied when it closes
  std::vector<int> keys_;          // presses since the last frame (GLFW key codes)
  std::optional<std::size_t> hovered_;
  const Bubble* hovered_bubble_ = nullptr;  // into status_.bubbles
  bool mouse_moved_ = false;
  long tracked_ = -1;
  std::vector<std::pair<double, double>> trajectory_;  // m, of the tracked particle
  std::int64_t trajectory_step_ = -1;
  float settle_edit_ = 0.5f, average_edit_ = 1.0f;  // the panel's fields (s)
  // The particles' fields (mm, kg/m^3), and the engine's changes of them taken so far.
  float diameter_edit_ = 4.0f, density_edit_ = 2700.0f;
  std::uint64_t particles_changes_ = 0;

  // A second bed beside the first, with its own engine thread: `--beside`, or the ideal twin the
  // panel started (own_twin_). Run, pause, step, reset, the gas and the live curve's times act on
  // both; the ideal case and the stiffness on the first only.
  ViewEngine* beside_ = nullptr;
  std::unique_ptr<ViewEngine> own_twin_;
  std::string beside_name_;
  std::shared_ptr<const Snapshot> beside_snap_;
  EngineStatus beside_status_;
  std::uint64_t beside_generation_ = 0;
  std::vector<float> beside_t_, beside_dp_;
  render::Rect beside_area_;  // window pixels
  int beside_w_ = 0;          // framebuffer px of its frame (frame_h_ high)

  // Plots (the last few thousand samples).
  std::uint64_t plot_generation_ = 0;
  std::vector<float> plot_t_, plot_dp_, plot_overlap_;

  // Screenshots and recording; the files the panel saves, numbered in the output folder.
  WindowCapture capture_;
  bool record_mp4_ = true;  // the panel's choice: an MP4, or PNG frames
  int counter_ = 0;
  std::string message_;  // the last thing written, or a problem (file names without folders)
  void say(const std::string& text);

  // The script.
  ScriptRunner script_;
  bool script_waiting_engine_ = false;
  bool script_finished_ = false;
  std::optional<std::chrono::steady_clock::time_point> script_wait_until_;
  bool script_wants_running_ = true;
  // Paused by the teacher inside the script (Run / Pause, space): the script waits, its `at T`
  // and its wall-clock wait resume where they were.
  bool held_ = false;
  double at_target_ = -1.0;  // s, the `at T` the engine runs to (< 0: none)
  std::optional<std::chrono::steady_clock::duration> held_wait_left_;
  bool lesson_over_ = false;  // a lesson's `quit` in the window
  bool quit_ = false;
  int exit_status_ = 0;

  // Tests drive the window with a pointer: $FLUIDBED_VIEW_WIDGETS names a file where the window
  // writes where its widgets are (docs/teaching.md).
  std::string widgets_file_;
  std::vector<std::string> widget_lines_;
  std::string widgets_written_;

  // Measurements.
  std::chrono::steady_clock::time_point t0_, last_status_t_;
  std::int64_t last_status_steps_ = 0;
  bool last_running_ = false;
  double draw_seconds_ = 0.0;
  ViewerStats stats_;
};

}  // namespace fluidbed::app
