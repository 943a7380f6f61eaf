#include "view/window.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "render/image.hpp"

namespace fluidbed::app {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

constexpr std::size_t kPlotPoints = 4000;  // samples kept for the plots
constexpr std::size_t kTrajectoryPoints = 20000;

template <class T>
void keep_last(std::vector<T>& v, std::size_t n) {
  if (v.size() > n + n / 4) v.erase(v.begin(), v.end() - static_cast<std::ptrdiff_t>(n));
}

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (auto* v = static_cast<Viewer*>(glfwGetWindowUserPointer(window))) v->key_event(key, action);
}

}  // namespace

Viewer::Viewer(ViewEngine& engine, ViewerOptions options)
    : engine_(engine),
      opt_(std::move(options)),
      look_(opt_.look),
      capture_([this](const std::string& said) { say(said); }),
      script_(opt_.script) {
  context_ = render::make_context("glfw", opt_.width, opt_.height);
  renderer_ = std::make_unique<render::Renderer>(*context_, opt_.font);
  stats_.gl_version = context_->version_string();
  auto* window = static_cast<GLFWwindow*>(context_->native_window());
  glfwSetWindowTitle(window, "fluidbed view");
  // Ours first: ImGui's key callback, installed next, calls it before its own.
  glfwSetWindowUserPointer(window, this);
  glfwSetKeyCallback(window, &on_key);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in the user's folder
  // Latin, Greek (eta, Delta p) and the signs the axes' tick labels use (a true minus, x 10 to a
  // superscript power).
  static const ImWchar ranges[] = {0x0020, 0x00FF, 0x0391, 0x03C9, 0x2070, 0x209F,
                                   0x2212, 0x2212, 0x2026, 0x2026, 0};
  for (float size : kPanelFontSizes)
    fonts_.emplace_back(size,
                        io.Fonts->AddFontFromFileTTF(opt_.font.c_str(), size, nullptr, ranges));
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 0.0f;
  imgui_glfw_ = ImGui_ImplGlfw_InitForOpenGL(window, true);
  // Dear ImGui's OpenGL 3 backend loads its own entry points (its gl3w, through libGL.so.1) for
  // the same context; the renderer keeps using its glad table.
  imgui_gl_ = imgui_glfw_ && ImGui_ImplOpenGL3_Init("#version 330 core");
  if (!imgui_gl_) {
    if (imgui_glfw_) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    throw std::runtime_error("the panel (Dear ImGui) could not start on this GL context");
  }
  if (look_.bubble_outlines) post({ViewCommand::Kind::bubbles, 1.0});
  look_.caption_band = true;
  // The slider's range, fixed while the particles are (a range that followed the live value ran
  // away under a held button): 2.5 U_mf, or beyond the scene's own velocity when that is higher.
  velocity_top_ = static_cast<float>(std::max({2.5 * opt_.umf, 1.25 * opt_.scene_velocity, 1.0}));
  diameter_edit_ = static_cast<float>(1000.0 * opt_.scene.particles.diameter);
  density_edit_ = static_cast<float>(opt_.scene.particles.density);
  const ViewEngine::Options& eo = engine_.options();
  settle_edit_ = static_cast<float>(eo.settle);
  average_edit_ = static_cast<float>(eo.average);
  if (const char* w = std::getenv("FLUIDBED_VIEW_WIDGETS"); w && *w) widgets_file_ = w;
  present_ = opt_.present;
  beside_ = opt_.beside;
  beside_name_ = opt_.beside_name;
}

void Viewer::key_event(int key, int action) {
  // A press acts once; a held `s` repeats (single steps).
  if (action == GLFW_PRESS || (action == GLFW_REPEAT && key == GLFW_KEY_S)) keys_.push_back(key);
}

Viewer::~Viewer() {
  try {
    capture_.stop_recording();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fluidbed view: %s\n", e.what());
  }
  if (auto* window = static_cast<GLFWwindow*>(context_->native_window()))
    glfwSetWindowUserPointer(window, nullptr);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  renderer_.reset();
  context_.reset();
}

void Viewer::post(const ViewCommand& c) {
  engine_.post(c);
  const bool both = c.kind != ViewCommand::Kind::ideal && c.kind != ViewCommand::Kind::stiffness;
  if (beside_ && both) beside_->post(c);
}

int Viewer::run() {
  t0_ = last_status_t_ = Clock::now();
  while (!quit_ && !context_->should_close()) frame();
  stats_.seconds = seconds_between(t0_, Clock::now());
  stats_.draw_ms = stats_.frames > 0 ? 1000.0 * draw_seconds_ / stats_.frames : 0.0;
  return exit_status_;
}

void Viewer::take_newest() {
  std::uint64_t seq = 0;
  auto s = engine_.snapshots().latest(&seq);
  const EngineStatus st = engine_.status();
  // Engine speed while the window is open (the benchmark): steps over the time it was stepping.
  const auto now = Clock::now();
  if (last_running_ && st.stepping) {
    stats_.engine_steps += st.steps - last_status_steps_;
    stats_.engine_seconds += seconds_between(last_status_t_, now);
  }
  last_running_ = st.stepping;
  last_status_steps_ = st.steps;
  last_status_t_ = now;
  if (st.generation != plot_generation_) {
    plot_generation_ = st.generation;
    plot_t_.clear();
    plot_dp_.clear();
    plot_overlap_.clear();
    trajectory_.clear();
    trajectory_step_ = -1;
  }
  for (const PlotSample& p : engine_.take_samples()) {
    plot_t_.push_back(static_cast<float>(p.t));
    plot_dp_.push_back(static_cast<float>(p.dp));
    plot_overlap_.push_back(static_cast<float>(p.max_overlap));
  }
  keep_last(plot_t_, kPlotPoints);
  keep_last(plot_dp_, kPlotPoints);
  keep_last(plot_overlap_, kPlotPoints);
  status_ = st;
  if (st.particles_changes != particles_changes_) {
    // New particles: their U_mf (the presets, the slider's tick and range) and their step.
    particles_changes_ = st.particles_changes;
    opt_.umf = st.umf;
    opt_.umf_cached = st.umf_cached;
    opt_.umf_method = st.umf_method;
    opt_.umf_method_short = st.umf_method_short;
    opt_.dt = st.dt;
    velocity_top_ =
        static_cast<float>(std::max({2.5 * opt_.umf, 1.25 * opt_.scene_velocity, 1.0}));
  }
  take_beside();
  // The regime in words over the bed (from the last second's bubbles; gas beds only).
  look_.bed_label = st.bubbles && snap_ && snap_->has_gas() ? regime_words(*st.bubbles) : "";
  if (s && seq != snap_seq_) {
    snap_ = std::move(s);
    snap_seq_ = seq;
    if (tracked_ >= 0 && static_cast<std::size_t>(tracked_) < snap_->particles() &&
        snap_->step != trajectory_step_) {
      if (snap_->step < trajectory_step_) trajectory_.clear();
      trajectory_.emplace_back(snap_->x[static_cast<std::size_t>(tracked_)],
                               snap_->y[static_cast<std::size_t>(tracked_)]);
      trajectory_step_ = snap_->step;
      keep_last(trajectory_, kTrajectoryPoints);
    }
  }
}

void Viewer::frame() {
  const auto t_start = Clock::now();
  take_newest();
  if (!opt_.script.empty() && !lesson_over_ && exit_status_ == 0 &&
      (!status_.error.empty() || !status_.refusal.empty())) {
    // A script stops at a failure (status 3) or a refused command (bad input, status 2).
    const bool failed = !status_.error.empty();
    std::fprintf(stderr, "fluidbed: %s\n", (failed ? status_.error : status_.refusal).c_str());
    exit_status_ = failed ? 3 : 2;
    quit_ = true;
    return;
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  step_script();
  handle_keys();  // first: `p` changes the frame's place
  place_frame();
  handle_scene_input();
  widget_lines_.clear();
  draw_panel();
  draw_overlays();
  ImGui::Render();
  draw_scene();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  capture_.after_frame(*context_, [this](const std::string& path, const render::Image& img) {
    write_output(path, [&] { render::write_png(path, img); });
  });
  if (!widgets_file_.empty()) write_widgets();
  draw_seconds_ += seconds_between(t_start, Clock::now());
  context_->present();  // swaps and polls events
  ++stats_.frames;
  if (opt_.max_fps > 0.0) {  // the rest of the frame's time goes to the engine
    const auto next = t_start + std::chrono::duration_cast<Clock::duration>(
                                    std::chrono::duration<double>(1.0 / opt_.max_fps));
    std::this_thread::sleep_until(next);
  }
}

// The panel's size and font follow the window's; the bed's frame fills the rest at the
// framebuffer's resolution. The close-up is dropped when the area is too narrow for both panels
// (render::keeps_close_up); the caption band is always kept.
void Viewer::place_frame() {
  const ImGuiIO& io = ImGui::GetIO();
  panel_ = panel_layout(static_cast<int>(io.DisplaySize.x), static_cast<int>(io.DisplaySize.y));
  presenter_ =
      presenter_layout(static_cast<int>(io.DisplaySize.x), static_cast<int>(io.DisplaySize.y));
  // The presenter mode: the bed on the left, the words and Fig. 6 on the right (presenter.cpp).
  area_ = present_
              ? render::Rect{0.0f, 0.0f, std::max(16.0f, presenter_.bed_right),
                             std::max(16.0f, io.DisplaySize.y)}
              : render::Rect{panel_.width, 0.0f, std::max(panel_.width + 16.0f, io.DisplaySize.x),
                             std::max(16.0f, io.DisplaySize.y)};
  fb_scale_ = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
  frame_w_ = std::max(16, static_cast<int>(std::lround(area_.width() * fb_scale_)));
  frame_h_ = std::max(16, static_cast<int>(std::lround(area_.height() * fb_scale_)));
  // A bed beside: the area's right half is its (each bed whole, no close-up).
  beside_w_ = 0;
  if (beside_) {
    const float mid = std::round(0.5f * (area_.x0 + area_.x1));
    beside_area_ = {mid, area_.y0, area_.x1, area_.y1};
    area_.x1 = mid;
    frame_w_ = std::max(16, static_cast<int>(std::lround(area_.width() * fb_scale_)));
    beside_w_ = std::max(16, static_cast<int>(std::lround(beside_area_.width() * fb_scale_)));
  }
  if (!snap_) return;
  render::RenderSettings look = look_;
  // The presenter's bed, and two beds side by side: whole and large.
  look.close_up = present_ || beside_ ? 0.0 : opt_.look.close_up;
  if (look.close_up > 0.0 &&
      !render::keeps_close_up(*snap_, frame_w_, frame_h_, look.close_up, look.caption_band))
    look.close_up = 0.0;
  if (look.close_up != look_.close_up) look_.zoom = {};  // the panels changed
  look_.close_up = look.close_up;
  follow_tracked();
  layout_ = render::frame_layout_for(*snap_, look_, frame_w_, frame_h_);
}

// A tracked particle stays in sight: a zoomed panel's centre follows it.
void Viewer::follow_tracked() {
  if (tracked_ < 0 || !snap_ || static_cast<std::size_t>(tracked_) >= snap_->particles() ||
      look_.zoom.bed < 0)
    return;
  look_.zoom.x = snap_->x[static_cast<std::size_t>(tracked_)];
  look_.zoom.y = snap_->y[static_cast<std::size_t>(tracked_)];
}

float Viewer::to_window_x(double fx) const {
  return area_.x0 + static_cast<float>(fx) / fb_scale_;
}
float Viewer::to_window_y(double fy) const {
  return area_.y0 + static_cast<float>(fy) / fb_scale_;
}

void Viewer::draw_scene() {
  const auto& gl = context_->gl();
  const int fbw = context_->width(), fbh = context_->height();
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.Viewport(0, 0, fbw, fbh);
  gl.ClearColor(0.96f, 0.96f, 0.95f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  if (snap_) {
    // Two beds side by side: each named in its caption band (a lesson's caption wins).
    render::RenderSettings look = look_;
    if (beside_ && look.caption.empty()) look.caption = opt_.scene.scene.name;
    renderer_->draw_frame(*snap_, look, frame_w_, frame_h_);
    const render::Rect src{0.0f, 0.0f, static_cast<float>(frame_w_), static_cast<float>(frame_h_)};
    const render::Rect dst{area_.x0 * fb_scale_, area_.y0 * fb_scale_,
                           area_.x0 * fb_scale_ + static_cast<float>(frame_w_),
                           area_.y0 * fb_scale_ + static_cast<float>(frame_h_)};
    renderer_->blit_region_to_default(src, dst, fbh);
  }
  draw_beside_frame();
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.Viewport(0, 0, fbw, fbh);
}

// Keys act on their press, queued by GLFW's callback: a tap shorter than a frame is not lost.
void Viewer::handle_keys() {
  std::vector<int> keys;
  keys.swap(keys_);
  if (ImGui::GetIO().WantCaptureKeyboard) return;  // typing into a field
  for (int key : keys) {
    switch (key) {
      case GLFW_KEY_SPACE:
        toggle_run();
        break;
      case GLFW_KEY_S:
        post({ViewCommand::Kind::step, 1.0});
        break;
      case GLFW_KEY_R:
        post({ViewCommand::Kind::reset, 0.0});
        break;
      case GLFW_KEY_C:
        cycle_colour();
        break;
      case GLFW_KEY_P:  // the presenter mode on or off; the bed's panels change
        present_ = !present_;
        look_.zoom = {};
        break;
      default:
        break;
    }
  }
}

void Viewer::handle_scene_input() {
  const ImGuiIO& io = ImGui::GetIO();
  hovered_.reset();
  hovered_bubble_ = nullptr;
  const ImVec2 m = io.MousePos;
  const bool inside = m.x >= area_.x0 && m.x < area_.x1 && m.y >= area_.y0 && m.y < area_.y1;
  // A pointer that never moved (a virtual display, a scripted demo) points at nothing.
  if (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f) mouse_moved_ = true;
  if (io.WantCaptureMouse || !inside || !snap_ || !mouse_moved_) return;
  const double fx = (m.x - area_.x0) * fb_scale_, fy = (m.y - area_.y0) * fb_scale_;
  const int bed = render::bed_at(layout_, fx, fy);
  double wx = 0.0, wy = 0.0;
  const bool in_bed = render::frame_to_world(layout_, fx, fy, wx, wy);
  // The wheel zooms the panel under the pointer about the point under it; dragging pans it.
  if (io.MouseWheel != 0.0f && bed >= 0 && in_bed) {
    const render::BedView& b = layout_.beds[static_cast<std::size_t>(bed)];
    // Unzoomed, the panel's centre shows the middle of the part of the bed it holds.
    render::BedZoom z = look_.zoom.bed == bed
                            ? look_.zoom
                            : render::BedZoom{bed, 1.0, 0.5 * b.inside.width() / b.scale,
                                              0.5 * b.inside.height() / b.scale};
    const double before = z.factor;
    z.factor = std::clamp(z.factor * std::pow(1.2, static_cast<double>(io.MouseWheel)), 1.0, 16.0);
    // Keep (wx, wy) under the pointer: the centre moves toward it by 1 - before / after.
    z.x += (wx - z.x) * (1.0 - before / z.factor);
    z.y += (wy - z.y) * (1.0 - before / z.factor);
    look_.zoom = z.factor > 1.0 ? z : render::BedZoom{};
    layout_ = render::frame_layout_for(*snap_, look_, frame_w_, frame_h_);
  }
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left) ||
      ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
    if (look_.zoom.bed >= 0) {
      const double s = layout_.beds[static_cast<std::size_t>(look_.zoom.bed)].scale / fb_scale_;
      look_.zoom.x -= io.MouseDelta.x / s;
      look_.zoom.y += io.MouseDelta.y / s;
    }
    return;
  }
  if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Right)) look_.zoom = {};
  hovered_ = render::pick_particle(*snap_, layout_, fx, fy);
  if (in_bed && status_.bubbles) hovered_bubble_ = status_.bubbles->region_at(wx, wy);
  // A click (no drag) picks the particle to track; a click on nothing stops tracking.
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
      ImGui::GetMouseDragDelta(ImGuiMouseButton_Left, 0.0f).x == 0.0f &&
      ImGui::GetMouseDragDelta(ImGuiMouseButton_Left, 0.0f).y == 0.0f) {
    tracked_ = hovered_ ? static_cast<long>(*hovered_) : -1;
    trajectory_.clear();
    trajectory_step_ = -1;
  }
  if (hovered_ || hovered_bubble_) draw_hover_tooltip(hovered_, hovered_bubble_);
}

// Run or pause as the button says. Inside a script that runs the bed (a lesson), Pause holds
// the script where it is (its `at T` and its wait included) and Run goes on from there; the
// teacher may step in between.
void Viewer::toggle_run() {
  const bool in_script = !opt_.script.empty() && !script_finished_ && !quit_;
  if (in_script && held_) {
    held_ = false;
    if (held_wait_left_) {
      script_wait_until_ = Clock::now() + *held_wait_left_;
      held_wait_left_.reset();
    }
    if (at_target_ >= 0.0)
      post({ViewCommand::Kind::run_until, at_target_});
    else if (script_wait_until_ && script_wants_running_)
      post({ViewCommand::Kind::run, 0.0});
    return;
  }
  const bool pause = bed_is_running();
  if (in_script && pause && script_runs_the_bed()) {
    held_ = true;
    if (script_wait_until_) {
      held_wait_left_ = std::max(Clock::duration::zero(), *script_wait_until_ - Clock::now());
      script_wait_until_.reset();
    }
    post({ViewCommand::Kind::pause, 0.0});
    return;
  }
  if (!opt_.script.empty()) script_wants_running_ = !pause;
  post({pause ? ViewCommand::Kind::pause : ViewCommand::Kind::run, 0.0});
}

// The panel's buttons in turn (the viewer's colour words, render/colour_by.hpp).
void Viewer::cycle_colour() {
  using render::ColourBy;
  std::vector<ColourBy> order;
  for (const render::ColourByName& mode : render::kColourByNames)
    if (render::is_viewer_name(mode)) order.push_back(mode.value);
  // A monolayer's depth is one colour (every centre on the mid-plane): the key skips it there.
  const bool thick = snap_ && !snap_->z.empty();
  std::size_t k = 0;
  while (k < order.size() && order[k] != look_.colour_by) ++k;
  do {
    k = (k + 1) % order.size();
  } while (order[k] == ColourBy::depth && !thick);
  render::set_colour_by(look_, order[k]);
}

// The script (view/script_runner.hpp): the runner calls the commands below one after the
// other; `at T` first runs the engine to T and waits for it.
void Viewer::step_script() {
  script_.advance(*this);
  if (!script_finished_ && !quit_ && script_.at_end() && !script_waiting_engine_ &&
      !script_.empty()) {
    script_finished_ = true;
    if (script_wants_running_) post({ViewCommand::Kind::run, 0.0});
  }
}

void Viewer::run_to(double t) {
  post({ViewCommand::Kind::run_until, t});
  at_target_ = t;
  script_waiting_engine_ = true;
}

bool Viewer::busy() {
  if (held_) return true;  // the teacher paused the script
  for (;;) {
    if (script_waiting_engine_) {
      if (!engine_.wait_until_stopped(std::chrono::milliseconds(0))) return true;
      if (beside_ && !beside_->wait_until_stopped(std::chrono::milliseconds(0))) return true;
      script_waiting_engine_ = false;
      at_target_ = -1.0;
      take_newest();  // the state where it stopped
    }
    if (!script_wait_until_) break;
    if (Clock::now() < *script_wait_until_) return true;
    script_wait_until_.reset();
    post({ViewCommand::Kind::pause, 0.0});
    script_waiting_engine_ = true;
  }
  return capture_.screenshot_pending();  // drawn and written first
}

void Viewer::unsupported(const ScriptLine& l) {
  // Every command has a meaning in the window; a new one that is not carried out here says so.
  std::fprintf(stderr, "fluidbed view: script line %d has no effect in the window\n", l.line);
}

bool Viewer::velocity(double u) {
  set_velocity(u);
  return true;
}

void Viewer::set_velocity(double u) {
  velocity_ = static_cast<float>(u);
  post({ViewCommand::Kind::velocity, u});
}

bool Viewer::ideal(bool on) {
  post({ViewCommand::Kind::ideal, on ? 1.0 : 0.0});
  script_waiting_engine_ = true;
  return true;
}

bool Viewer::stiffness(double k) {
  post({ViewCommand::Kind::stiffness, k});
  script_waiting_engine_ = true;
  return true;
}

bool Viewer::particles(double diameter, double density) {
  if (diameter > 0.0) {
    diameter_edit_ = static_cast<float>(1000.0 * diameter);
    density_edit_ = static_cast<float>(density);
  }
  post({ViewCommand::Kind::particles, diameter, density});
  script_waiting_engine_ = true;
  return true;
}

bool Viewer::settle(double seconds) {
  settle_edit_ = static_cast<float>(seconds);
  post({ViewCommand::Kind::settle, seconds});
  script_waiting_engine_ = true;
  return true;
}

bool Viewer::average(double seconds) {
  average_edit_ = static_cast<float>(seconds);
  post({ViewCommand::Kind::average, seconds});
  script_waiting_engine_ = true;
  return true;
}

bool Viewer::save_curve(const std::string& file) {
  save_curve_file(file);
  return true;
}

bool Viewer::caption(const std::string& text) {
  look_.caption = text;
  return true;
}

bool Viewer::run_switch(bool running) {
  script_wants_running_ = running;  // applied when a wait or the end of the script lets it run
  return true;
}

bool Viewer::step(double count) {
  post({ViewCommand::Kind::step, count});
  script_waiting_engine_ = true;
  return true;
}

bool Viewer::reset() {
  post({ViewCommand::Kind::reset, 0.0});
  script_waiting_engine_ = true;
  return true;
}

bool Viewer::wait(double wall_seconds) {
  if (script_wants_running_) post({ViewCommand::Kind::run, 0.0});
  script_wait_until_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(wall_seconds));
  return true;
}

bool Viewer::colour(const std::string& mode) {
  render::set_colour_by(look_, render::parse_viewer_colour(mode));
  return true;
}

bool Viewer::gas_arrows(bool on) {
  look_.gas_arrows = on;
  return true;
}

bool Viewer::particle_arrows(bool on) {
  look_.particle_arrows = on;
  return true;
}

bool Viewer::porosity(bool on) {
  look_.porosity_background = on;
  return true;
}

bool Viewer::bubbles(bool on) {
  look_.bubble_outlines = on;
  post({ViewCommand::Kind::bubbles, on ? 1.0 : 0.0});
  return true;
}

bool Viewer::track(long id, int line) {
  if (snap_ && id >= static_cast<long>(snap_->particles())) {
    std::fprintf(stderr, "fluidbed: error: script line %d: no particle %ld (0 to %zu)\n", line, id,
                 snap_->particles() - 1);
    exit_status_ = 2;
    quit_ = true;
    return true;
  }
  tracked_ = id;
  trajectory_.clear();
  trajectory_step_ = -1;
  return true;
}

// The close-up when there is one (the whole bed otherwise), about the tracked particle (which it
// then follows) or the panel's middle.
bool Viewer::zoom(double factor) {
  if (factor <= 1.0 || layout_.beds.empty()) {
    look_.zoom = {};
    return true;
  }
  const int bed = layout_.beds.size() > 1 ? 1 : 0;
  const render::BedView& b = layout_.beds[static_cast<std::size_t>(bed)];
  const double w = b.inside.width() / b.scale, h = b.inside.height() / b.scale;
  look_.zoom = look_.zoom.bed == bed ? look_.zoom : render::BedZoom{bed, 1.0, 0.5 * w, 0.5 * h};
  look_.zoom.factor = factor;
  follow_tracked();
  return true;
}

bool Viewer::screenshot(const std::string& file) {
  capture_.screenshot(file);
  capture_.settle(2);  // ImGui lays a changed panel out over a frame or two
  return true;
}

bool Viewer::record(const std::string& target) {
  try {
    start_recording(target);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fluidbed: output failed: %s\n", e.what());
    exit_status_ = 4;
    quit_ = true;
  }
  return true;
}

bool Viewer::record_stop() {
  capture_.stop_recording();
  return true;
}

void Viewer::start_recording(const std::string& target) {
  capture_.start_recording(target, context_->width(), context_->height());
}

bool Viewer::quit() {
  if (!opt_.lesson) {
    quit_ = true;
    return true;
  }
  // A lesson's end in the window: the bed stops, the last picture and the curve stay on the
  // screen until the window is closed, and the panel's controls go on working.
  lesson_over_ = true;
  script_finished_ = true;
  post({ViewCommand::Kind::pause, 0.0});
  say("The lesson is over. Its last picture stays until you close the window; Run goes on with "
      "the bed.");
  return true;
}

}  // namespace fluidbed::app
