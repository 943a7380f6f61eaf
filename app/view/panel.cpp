// The viewer's control panel (Dear ImGui). A block at the top that never scrolls (run control,
// pictures, time and speed, what went wrong), then sections that scroll: the gas with the stages
// of Fig. 6, the live Fig. 6, bubbles and the regime, the plots, colours and layers, the picked
// particle. Every edit of the simulation goes to the engine as a command.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/text_format.hpp"
#include "render/colour_map.hpp"
#include "run/umf_estimate.hpp"
#include "view/presets.hpp"
#include "view/status_words.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

// The overlap above which the panel warns: about twice the largest the teaching bed reaches in
// its own run after start-up (2.8 %, docs/studies.md); the paper's stiff bed stays near 1 %.
constexpr double kOverlapWarning = 0.05;

ImU32 to_imgui(const render::Rgb& c) {
  return IM_COL32(static_cast<int>(c.r * 255.0f), static_cast<int>(c.g * 255.0f),
                  static_cast<int>(c.b * 255.0f), 255);
}

std::string fmt(const char* f, double a) { return format_number(f, a); }

// A horizontal colour bar of the scale with its two ends labelled.
void colour_bar(const render::ColourScale& scale) {
  const float w = ImGui::GetContentRegionAvail().x, h = 0.9f * ImGui::GetFontSize();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  constexpr int kSteps = 48;
  for (int k = 0; k < kSteps; ++k) {
    const double t0 = static_cast<double>(k) / kSteps, t1 = static_cast<double>(k + 1) / kSteps;
    const double value = render::scale_value(scale, t0 + 0.5 / kSteps);
    const ImU32 c = to_imgui(
        render::colour_at(render::ColourMap::viridis, render::scale_position(scale, value)));
    dl->AddRectFilled(ImVec2(p.x + static_cast<float>(t0) * w, p.y),
                      ImVec2(p.x + static_cast<float>(t1) * w + 0.5f, p.y + h), c);
  }
  ImGui::Dummy(ImVec2(w, h));
  ImGui::Text("%.3g", scale.min);
  ImGui::SameLine();
  const char* title = scale.title.c_str();
  ImGui::SetCursorPosX(std::max(ImGui::GetCursorPosX(), 0.5f * (w - ImGui::CalcTextSize(title).x)));
  ImGui::TextUnformatted(title);
  char hi[32];
  std::snprintf(hi, sizeof hi, "%.3g", scale.max);
  ImGui::SameLine();
  ImGui::SetCursorPosX(std::max(ImGui::GetCursorPosX(), w - ImGui::CalcTextSize(hi).x));
  ImGui::TextUnformatted(hi);
}

// Wrapped text in a colour.
void wrapped(const ImVec4& colour, const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

const ImVec4 kRed(1.0f, 0.45f, 0.35f, 1.0f), kOrange(1.0f, 0.75f, 0.3f, 1.0f);

}  // namespace

void Viewer::note_widget(const char* name, const std::string& value) {
  if (widgets_file_.empty()) return;
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  char line[256];
  std::snprintf(line, sizeof line, "%s %.1f %.1f %.1f %.1f %s", name, a.x, a.y, b.x, b.y,
                value.c_str());
  widget_lines_.emplace_back(line);
}

void Viewer::draw_particle_info(std::size_t i, bool tooltip) {
  if (!snap_ || i >= snap_->particles()) return;
  const Snapshot& s = *snap_;
  const render::ParticleContacts c = render::contacts_of(s, i);
  ImGui::Text("particle %zu%s", i, tooltip ? "   (click: track)" : "");
  if (i < s.z.size())
    ImGui::Text("position  %.4f, %.4f m, %.4f m behind the front", s.x[i], s.y[i], s.z[i]);
  else
    ImGui::Text("position  %.4f, %.4f m", s.x[i], s.y[i]);
  if (i < s.vz.size() && i < s.fz.size()) {  // a thick bed: three components
    ImGui::Text("velocity  %.3f, %.3f, %.3f m/s (|v| %.3f)", s.vx[i], s.vy[i], s.vz[i], s.speed(i));
    ImGui::Text("force     %.3g, %.3g, %.3g N (|F| %.3g)", s.fx[i], s.fy[i], s.fz[i], s.force(i));
    ImGui::Text("torque    |T| %.3g N m (about z %.3g)", s.torque_magnitude(i), s.torque[i]);
  } else {
    ImGui::Text("velocity  %.3f, %.3f m/s (|v| %.3f)", s.vx[i], s.vy[i], s.speed(i));
    ImGui::Text("force     %.3g, %.3g N (|F| %.3g)", s.fx[i], s.fy[i], s.force(i));
    ImGui::Text("torque    %.3g N m   spin %.3g rad/s", s.torque[i], s.spin[i]);
  }
  ImGui::Text("contacts  %zu (%zu particles, %d walls), overlap %.2g", c.count(),
              c.particles.size(), c.walls, i < s.overlap.size() ? s.overlap[i] : c.max_overlap);
}

bool Viewer::bed_is_running() const {
  return status_.running || status_.stepping || script_runs_the_bed();
}

bool Viewer::script_runs_the_bed() const {
  // A script that runs the bed from one `at T` to the next is running it, even at the instant
  // it stopped there for a screenshot.
  return !opt_.script.empty() && !script_finished_ && script_wants_running_ && !quit_ && !held_;
}

void Viewer::draw_top_block() {
  const EngineStatus& st = status_;
  const float button = 4.6f * ImGui::GetFontSize();
  const char* run_label = bed_is_running() ? "Pause" : "Run";
  if (ImGui::Button(run_label, ImVec2(button, 0))) toggle_run();
  note_widget("run_button", run_label);
  ImGui::SameLine();
  if (ImGui::Button("Step", ImVec2(button, 0))) post({ViewCommand::Kind::step, 1.0});
  note_widget("step_button");
  ImGui::SameLine();
  if (ImGui::Button("Reset", ImVec2(button, 0))) post({ViewCommand::Kind::reset, 0.0});
  note_widget("reset_button");
  if (ImGui::Button("Screenshot", ImVec2(button * 1.5f, 0)))
    capture_.screenshot(next_name("screenshot", ".png"));
  note_widget("screenshot_button");
  ImGui::SameLine();
  const bool recording = capture_.recording();
  if (ImGui::Button(recording ? "Stop recording" : "Record", ImVec2(button * 1.5f, 0))) {
    try {
      if (recording)
        capture_.stop_recording();
      else
        start_recording(next_name("recording", record_mp4_ ? ".mp4" : ""));
    } catch (const std::exception& e) {
      say(e.what());
    }
  }
  note_widget("record_button", recording ? "recording" : "idle");
  if (!recording) {
    ImGui::SameLine();
    if (ImGui::RadioButton("MP4", record_mp4_)) record_mp4_ = true;
    ImGui::SameLine();
    if (ImGui::RadioButton("PNG", !record_mp4_)) record_mp4_ = false;
  }

  // Time, what the bed is doing, and its speed in words a class understands.
  std::string state = run_state_words(st, script_runs_the_bed());
  if (held_ && !st.stepping) state = "paused: the lesson waits (Run goes on)";
  if (lesson_over_ && !st.stepping && st.error.empty()) state = "the lesson is over";
  ImGui::Text("t = %.4f s   step %lld", st.time, static_cast<long long>(st.steps));
  note_widget("time", fmt("%.9g", st.time));
  ImGui::TextUnformatted(state.c_str());
  note_widget("state", state);
  const std::string speed = speed_words(st.sim_s_per_wall_s);
  ImGui::TextUnformatted(speed.c_str());
  note_widget("speed", speed);
  ImGui::TextDisabled("%.0f steps/s, window %.0f frames/s", st.steps_per_s,
                      static_cast<double>(ImGui::GetIO().Framerate));
  ImGui::Separator();
}

// What went wrong, what to mind, what was written: in a fixed area at the panel's foot, which
// scrolls when a message is longer than it, so that no control moves under the pointer when a
// message comes or goes. For a class (the presenter mode): the failure without the engine's
// words, a blown-out bed in one sentence, no overlap warning.
void Viewer::draw_messages(bool for_a_class) {
  const EngineStatus& st = status_;
  const std::string& error = for_a_class ? st.error_plain : st.error;
  if (!error.empty()) wrapped(kRed, error);
  note_widget(for_a_class ? "present_error" : "error", error.empty() ? "none" : "shown");
  if (!st.refusal.empty()) wrapped(kOrange, st.refusal);
  if (for_a_class) {
    if (st.held_at_top > 0)
      wrapped(kOrange,
              "The gas has blown the bed against the top screen. Lower the gas and press "
              "Reset.");
    if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
    return;
  }
  // Deep overlaps (a high gas velocity) are warned of while they last.
  if (!plot_overlap_.empty()) {
    const std::size_t recent = std::min<std::size_t>(plot_overlap_.size(), 500);
    const float worst = *std::max_element(plot_overlap_.end() - static_cast<std::ptrdiff_t>(recent),
                                          plot_overlap_.end());
    if (worst > kOverlapWarning) {
      wrapped(kOrange, fmt("Overlap %.1f %%", 100.0 * worst) +
                           fmt(" (warning above %.0f %%): the particles are pressed deeper into "
                               "each other than the contact model is meant for. Lower the gas.",
                               100.0 * kOverlapWarning));
      note_widget("overlap_warning", fmt("%.4f", worst));
    }
  }
  if (st.held_at_top > 0) {
    wrapped(kOrange,
            std::to_string(st.held_at_top) +
                " spheres have been held against the top screen for over a second: the gas has "
                "blown the bed out, and dp is the screen's push, not the bed's weight. Lower the "
                "gas and press Reset to start again from the packed bed.");
    note_widget("blown_out", std::to_string(st.held_at_top));
  }
  if (!message_.empty()) {
    ImGui::TextWrapped("%s", message_.c_str());
    note_widget("message", message_);
  }
}

void Viewer::draw_gas_section() {
  const EngineStatus& st = status_;
  if (!ImGui::CollapsingHeader("Gas and the stages of Fig. 6", ImGuiTreeNodeFlags_DefaultOpen))
    return;
  velocity_slider("U = %.2f m/s");
  ImGui::TextDisabled("Ctrl+click the slider to type a velocity, Enter to apply it");
  ImGui::Text("jet %.1f m/s (fastest inlet face %.1f m/s)", st.jet_velocity, st.inlet_jet_velocity);
  if (opt_.umf > 0.0) {
    // The live number on a line of its own: wrapped with the words after it, a change of U
    // could move a word to the next line and every control below it.
    ImGui::Text("U_mf = %.2f m/s (U = %.2f U_mf)", opt_.umf, st.superficial_velocity / opt_.umf);
    ImGui::TextWrapped("U_mf from %s%s.", opt_.umf_method.c_str(),
                       opt_.umf_cached ? " (from the cache)" : "");
    const float half = 0.5f * (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x);
    for (std::size_t k = 0; k < std::size(kPresets); ++k) {
      const Preset& p = kPresets[k];
      const double u = p.umf_multiple * opt_.umf;
      char label[96];
      std::snprintf(label, sizeof label, "%s %.2f", p.label, u);
      if (k % 2 == 1) ImGui::SameLine();
      if (ImGui::Button(label, ImVec2(half, 0))) set_velocity(u);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%.2f U_mf = %.2f m/s: %s", p.umf_multiple, u, p.what);
      note_widget((std::string("preset_") + p.name).c_str(), fmt("%.6g", u));
    }
    fig6_button(ImVec2(-1.0f, 0.0f));
  }
  if (ImGui::Button(st.ideal ? "Back to the scene's contacts" : "Ideal case (eta = 0, gamma = 0)"))
    post({ViewCommand::Kind::ideal, st.ideal ? 0.0 : 1.0});
  const char* ideal = st.ideal ? ", damping 0, friction 0" : "";
  if (st.stiffness > 0.0)
    ImGui::Text("contacts: %.0f N/m%s", st.stiffness, ideal);
  else
    ImGui::Text("contacts: Hertz-Mindlin%s", ideal);
  draw_beside_section();
}

// The gas velocity's slider, full width, with U_mf and the scene's velocity ticked under it.
void Viewer::velocity_slider(const char* format) {
  const EngineStatus& st = status_;
  // Dragged, the velocity applies as the pointer moves; typed (Ctrl+click), it is clamped to the
  // range and applies when the field closes (Enter, or a click elsewhere), never digit by digit.
  if (typed_velocity_ && !ImGui::IsAnyItemActive()) {
    typed_velocity_ = false;
    set_velocity(std::clamp(static_cast<double>(velocity_), 0.0,
                            static_cast<double>(velocity_top_)));
  }
  if (!ImGui::IsAnyItemActive()) velocity_ = static_cast<float>(st.superficial_velocity);
  ImGui::SetNextItemWidth(-1.0f);
  // A fixed range (set when the window opened): the value under a held pointer stays where it is.
  const bool typing = ImGui::GetIO().WantTextInput;
  if (ImGui::SliderFloat("##U", &velocity_, 0.0f, velocity_top_, format,
                         ImGuiSliderFlags_AlwaysClamp)) {
    if (typing)
      typed_velocity_ = true;
    else
      set_velocity(static_cast<double>(velocity_));
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Ctrl+click to type a velocity, Enter to apply it");
  note_widget("velocity_slider", fmt("0 %.6g", velocity_top_) +
                                     fmt(" %.1f", ImGui::GetStyle().GrabMinSize) +
                                     fmt(" %.6g", st.superficial_velocity));
  {  // Ticks under the slider: U_mf and the scene's own velocity.
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    const float grab = ImGui::GetStyle().GrabMinSize, pad = 2.0f;
    const auto x_of = [&](double u) {
      return a.x + pad + 0.5f * grab +
             static_cast<float>(u / velocity_top_) * (b.x - a.x - 2.0f * pad - grab);
    };
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float h = ImGui::GetFontSize();
    const ImVec2 row = ImGui::GetCursorScreenPos();
    // Two labels that would overlap are put side by side, the lower velocity's on the left.
    struct Tick {
      double u;
      const char* text;
      ImU32 colour;
    };
    Tick ticks[] = {{opt_.umf, "U_mf", IM_COL32(255, 200, 90, 255)},
                    {opt_.scene_velocity, "scene", IM_COL32(160, 200, 255, 255)}};
    if (ticks[1].u < ticks[0].u) std::swap(ticks[0], ticks[1]);
    float right = a.x - 1e9f;
    for (const Tick& t : ticks) {
      if (!(t.u > 0.0) || t.u > velocity_top_) continue;
      const float x = x_of(t.u);
      dl->AddLine(ImVec2(x, b.y), ImVec2(x, b.y + 0.35f * h), t.colour, 2.0f);
      const float w = ImGui::CalcTextSize(t.text).x;
      const float left = std::clamp(std::max(x - 0.5f * w, right + 0.4f * h), a.x, b.x - w);
      dl->AddText(ImVec2(left, row.y + 0.1f * h), t.colour, t.text);
      right = left + w;
    }
    ImGui::Dummy(ImVec2(b.x - a.x, 1.2f * h));
  }
}

// Fig. 6 from the start in one action: the packed bed at the fixed-bed preset, running, the
// curve empty (not while a script runs the bed).
void Viewer::fig6_button(const ImVec2& size) {
  const Preset* fixed = find_preset("fixed");
  if (!fixed || !(opt_.umf > 0.0)) return;
  const bool scripted = script_runs_the_bed() || held_;
  const double u = fixed->umf_multiple * opt_.umf;
  if (ImGui::Button("Fig. 6 from the packed bed", size) && !scripted) {
    set_velocity(u);  // Reset keeps it: the packed bed at this velocity
    post({ViewCommand::Kind::reset, 0.0});
    if (!opt_.script.empty()) script_wants_running_ = true;
    post({ViewCommand::Kind::run, 0.0});
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Back to the packed bed at %.2f m/s (%.1f U_mf) and run: then raise U a "
        "step at a time through U_mf, and lower it again",
        u, fixed->umf_multiple);
  note_widget("fig6_button", fmt("%.6g", u));
}

void Viewer::draw_curve_section() {
  if (!ImGui::CollapsingHeader("Fig. 6 live: pressure drop against U",
                               ImGuiTreeNodeFlags_DefaultOpen))
    return;
  const CurveState& c = status_.curve;
  draw_curve_plot(11.0f * ImGui::GetFontSize());
  ImGui::TextWrapped("%s", describe_phase(c).c_str());
  if (c.umf.ok) {
    // A rough figure beside the scene's measured one: a few points of a short average each.
    std::size_t points = 0;
    if (!c.branches.empty() && !c.branches.back().increasing)
      points = c.branches.back().points.size();
    std::string text = fmt("U_mf from this curve's way down: %.2f m/s, rough (", c.umf.umf) +
                       std::to_string(points) +
                       fmt(" points, each the mean of %.1f s; a sweep averages longer).", c.window);
    if (opt_.umf > 0.0)
      text += fmt(" The slider's tick and the presets use %.2f m/s, measured above.", opt_.umf);
    ImGui::TextWrapped("%s", text.c_str());
  } else {
    ImGui::TextDisabled("U_mf: lower U in steps through the bed's U_mf");
  }
  // Settling time and averaging window, simulated seconds.
  const float field = 4.0f * ImGui::GetFontSize();
  ImGui::SetNextItemWidth(field);
  if (ImGui::InputFloat("settle (s)", &settle_edit_, 0.0f, 0.0f, "%.2f",
                        ImGuiInputTextFlags_EnterReturnsTrue) ||
      ImGui::IsItemDeactivatedAfterEdit())
    post({ViewCommand::Kind::settle, std::max(0.0, static_cast<double>(settle_edit_))});
  ImGui::SameLine();
  ImGui::SetNextItemWidth(field);
  if (ImGui::InputFloat("average (s)", &average_edit_, 0.0f, 0.0f, "%.2f",
                        ImGuiInputTextFlags_EnterReturnsTrue) ||
      ImGui::IsItemDeactivatedAfterEdit())
    post({ViewCommand::Kind::average, std::max(0.01, static_cast<double>(average_edit_))});
  if (!ImGui::IsAnyItemActive()) {
    settle_edit_ = static_cast<float>(c.settle);
    average_edit_ = static_cast<float>(c.window);
  }
  if (ImGui::Button("Save CSV")) save_curve_file(next_name("curve", ".csv"));
  ImGui::SameLine();
  if (ImGui::Button("Save PNG")) save_curve_file(next_name("curve", ".png"));
  ImGui::SameLine();
  ImGui::TextDisabled("Reset clears it");
}

void Viewer::draw_bed_section() {
  if (!ImGui::CollapsingHeader("Bubbles and the regime", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (const auto& v = status_.bubbles; v && snap_ && snap_->has_gas()) {
    const BubbleStatistics& w = v->window;
    ImGui::Text("regime (last %.1f s): %s", v->window_s, regime_words(*v).c_str());
    note_widget("regime", regime_words(*v));
    std::string line = fmt("%.1f bubbles formed per s", w.formed_per_s);
    if (std::isfinite(w.mean_d_eq_m) && w.bubble_frames > 0)
      line += fmt(", mean size %.0f mm", 1000.0 * w.mean_d_eq_m);
    if (const std::string rise = mean_rise_words(w); !rise.empty()) line += ", " + rise;
    line += fmt("; a slug in %.0f %% of the frames", 100.0 * w.slugging_fraction);
    ImGui::TextWrapped("%s", line.c_str());
  } else {
    ImGui::TextDisabled("(no gas: no bubbles)");
  }
  if (ImGui::Checkbox("bubble outlines", &look_.bubble_outlines))
    post({ViewCommand::Kind::bubbles, look_.bubble_outlines ? 1.0 : 0.0});
  ImGui::SameLine();
  ImGui::TextDisabled("hover a bubble: its size");
}

// Other spheres, the count kept: a packed bed of them in seconds (packed once, then cached).
void Viewer::draw_particles_section() {
  if (!ImGui::CollapsingHeader("Particle size and density")) return;
  const EngineStatus& st = status_;
  const bool own = st.particle_diameter == opt_.scene.particles.diameter &&
                   st.particle_density == opt_.scene.particles.density;
  ImGui::TextWrapped("%zu spheres of %.1f mm, %.0f kg/m^3%s; time step %.3g s", st.particles,
                     1000.0 * st.particle_diameter, st.particle_density,
                     own ? " (the scene's)" : "", st.dt);
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::SliderFloat("##diameter", &diameter_edit_, 2.0f, 6.0f, "diameter %.1f mm",
                     ImGuiSliderFlags_AlwaysClamp);
  note_widget("diameter", fmt("%.4g", diameter_edit_));
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::SliderFloat("##density", &density_edit_, 500.0f, 8000.0f, "density %.0f kg/m^3",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  note_widget("density", fmt("%.5g", density_edit_));
  ImGui::BeginDisabled(!st.busy.empty());
  if (ImGui::Button("Pack a bed of these"))
    post({ViewCommand::Kind::particles, 0.001 * static_cast<double>(diameter_edit_),
          static_cast<double>(density_edit_)});
  note_widget("pack_particles");
  ImGui::SameLine();
  if (ImGui::Button("The scene's particles")) {
    diameter_edit_ = static_cast<float>(1000.0 * opt_.scene.particles.diameter);
    density_edit_ = static_cast<float>(opt_.scene.particles.density);
    post({ViewCommand::Kind::particles, 0.0, 0.0});
  }
  ImGui::EndDisabled();
  if (!st.busy.empty())
    ImGui::TextWrapped("%s ...", st.busy.c_str());
  else
    ImGui::TextDisabled("glass 2500, steel 7800, nylon 1150 kg/m^3");
}

void Viewer::draw_look_section() {
  if (!ImGui::CollapsingHeader("Colours and layers")) return;
  using render::ColourBy;
  std::size_t k = 0;  // the viewer's words in the table's order, three to a row
  for (const render::ColourByName& mode : render::kColourByNames) {
    if (!render::is_viewer_name(mode)) continue;
    if (k > 0 && k != 3) ImGui::SameLine();
    ++k;
    const std::string label(mode.name);
    if (ImGui::RadioButton(label.c_str(), look_.colour_by == mode.value))
      render::set_colour_by(look_, mode.value);
  }
  if (snap_)
    colour_bar(render::colour_scale(look_.colour_by, *snap_, look_.range_min, look_.range_max,
                                    look_.height_bands));
  if (snap_ && look_.colour_by == ColourBy::depth && snap_->z.empty())
    ImGui::TextDisabled("a monolayer: every centre on the mid-plane");
  ImGui::Checkbox("gas arrows", &look_.gas_arrows);
  ImGui::SameLine();
  float gas_ref = static_cast<float>(look_.gas_arrow_reference);
  ImGui::SetNextItemWidth(-1.0f);
  if (ImGui::SliderFloat("##gasref", &gas_ref, 1.0f, 60.0f, "%.0f m/s per cell",
                         ImGuiSliderFlags_Logarithmic))
    look_.gas_arrow_reference = gas_ref;
  ImGui::Checkbox("particle arrows", &look_.particle_arrows);
  ImGui::SameLine();
  float part_ref = static_cast<float>(look_.particle_arrow_reference);
  ImGui::SetNextItemWidth(-1.0f);
  if (ImGui::SliderFloat("##partref", &part_ref, 0.05f, 5.0f, "%.2f m/s per 3 d",
                         ImGuiSliderFlags_Logarithmic))
    look_.particle_arrow_reference = part_ref;
  ImGui::Checkbox("porosity background", &look_.porosity_background);
  ImGui::Text("zoom %.1fx", look_.zoom.bed >= 0 ? look_.zoom.factor : 1.0);
  ImGui::SameLine();
  if (ImGui::SmallButton("1x")) look_.zoom = {};
}

ImFont* Viewer::font_of(float px) const {
  ImFont* font = fonts_.front().second;
  for (const auto& [size, f] : fonts_)
    if (size <= px) font = f;
  return font;
}

void Viewer::draw_panel() {
  if (present_) {
    draw_presenter();
    return;
  }
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(panel_.width, io.DisplaySize.y), ImGuiCond_Always);
  ImGui::Begin("fluidbed", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar);
  ImGui::PushFont(font_of(panel_.font));
  draw_top_block();
  // The messages' area: five lines of the panel's font at its foot.
  const float message_height =
      5.0f * ImGui::GetTextLineHeightWithSpacing() + 2.0f * ImGui::GetStyle().WindowPadding.y;
  ImGui::BeginChild("sections", ImVec2(0.0f, -message_height));
  draw_gas_section();
  draw_curve_section();
  draw_bed_section();
  if (ImGui::CollapsingHeader("dp and overlap against time", ImGuiTreeNodeFlags_DefaultOpen))
    draw_plots();
  draw_particles_section();
  draw_look_section();
  if (ImGui::CollapsingHeader("The picked particle", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (tracked_ >= 0 && snap_) {
      draw_particle_info(static_cast<std::size_t>(tracked_), false);
      if (ImGui::SmallButton("stop tracking")) {
        tracked_ = -1;
        trajectory_.clear();
      }
    } else {
      ImGui::TextDisabled("hover a particle; click to track it");
    }
  }
  ImGui::Separator();
  ImGui::TextDisabled(
      "space run/pause, s step, r reset, c colour, p presenter\nwheel: zoom the bed under the "
      "pointer,\n"
      "drag: pan, right double-click: 1x");
  ImGui::EndChild();
  ImGui::BeginChild("messages", ImVec2(0.0f, 0.0f), true);
  draw_messages();
  ImGui::EndChild();
  note_widget("messages");
  ImGui::PopFont();
  ImGui::End();
}

}  // namespace fluidbed::app
