// The viewer's control panel (Dear ImGui): run, gas, colours, arrows, plots, the picked particle,
// screenshots and recording. Every edit of the simulation goes to the engine as a command.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/colour_map.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

ImU32 to_imgui(const render::Rgb& c) {
  return IM_COL32(static_cast<int>(c.r * 255.0f), static_cast<int>(c.g * 255.0f),
                  static_cast<int>(c.b * 255.0f), 255);
}

// A horizontal colour bar of the scale with its two ends labelled.
void colour_bar(const render::ColourScale& scale) {
  const float w = ImGui::GetContentRegionAvail().x, h = 14.0f;
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  constexpr int kSteps = 48;
  for (int k = 0; k < kSteps; ++k) {
    const double t0 = static_cast<double>(k) / kSteps, t1 = static_cast<double>(k + 1) / kSteps;
    const double value = scale.min + (t0 + 0.5 / kSteps) * (scale.max - scale.min);
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

}  // namespace

void Viewer::draw_particle_info(std::size_t i, bool tooltip) {
  if (!snap_ || i >= snap_->particles()) return;
  const Snapshot& s = *snap_;
  const render::ParticleContacts c = render::contacts_of(s, i);
  ImGui::Text("particle %zu%s", i, tooltip ? "   (click: track)" : "");
  ImGui::Text("position  %.4f, %.4f m", s.x[i], s.y[i]);
  ImGui::Text("velocity  %.3f, %.3f m/s (|v| %.3f)", s.vx[i], s.vy[i],
              std::hypot(s.vx[i], s.vy[i]));
  ImGui::Text("force     %.3g, %.3g N (|F| %.3g)", s.fx[i], s.fy[i], std::hypot(s.fx[i], s.fy[i]));
  ImGui::Text("torque    %.3g N m   spin %.3g rad/s", s.torque[i], s.spin[i]);
  ImGui::Text("contacts  %zu (%zu particles, %d walls), overlap %.2g", c.count(),
              c.particles.size(), c.walls, i < s.overlap.size() ? s.overlap[i] : c.max_overlap);
}

void Viewer::draw_plots() {
  const int n = static_cast<int>(plot_t_.size());
  const float width = ImGui::GetContentRegionAvail().x;
  if (n < 2) {
    ImGui::TextDisabled("(the plots start when the bed runs)");
    return;
  }
  const std::size_t first =
      plot_t_.size() - static_cast<std::size_t>(std::min(n, static_cast<int>(plot_t_.size())));
  ImGui::Text("t from %.3f to %.3f s", plot_t_[first], plot_t_.back());
  const auto [dmin, dmax] = std::minmax_element(plot_dp_.begin(), plot_dp_.end());
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "dp %.0f Pa (%.0f to %.0f)", plot_dp_.back(), *dmin,
                *dmax);
  ImGui::PlotLines("##dp", plot_dp_.data(), n, 0, overlay, std::min(0.0f, *dmin),
                   std::max(*dmax, 1.0f), ImVec2(width, 70.0f));
  const float omax = *std::max_element(plot_overlap_.begin(), plot_overlap_.end());
  std::snprintf(overlay, sizeof overlay, "max overlap %.2f %% (peak %.2f %%)",
                100.0f * plot_overlap_.back(), 100.0f * omax);
  ImGui::PlotLines("##overlap", plot_overlap_.data(), n, 0, overlay, 0.0f, std::max(omax, 1e-4f),
                   ImVec2(width, 70.0f));
}

void Viewer::draw_panel() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(panel_width_, io.DisplaySize.y), ImGuiCond_Always);
  ImGui::Begin("fluidbed", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar);
  const EngineStatus& st = status_;
  ImGui::Text("fluidbed view   %zu particles", st.particles);
  ImGui::Separator();

  // Run control.
  if (ImGui::Button(st.running ? "Pause" : "Run", ImVec2(70, 0))) toggle_run();
  ImGui::SameLine();
  if (ImGui::Button("Step", ImVec2(70, 0))) post({ViewCommand::Kind::step, 1.0});
  ImGui::SameLine();
  if (ImGui::Button("Reset", ImVec2(70, 0))) post({ViewCommand::Kind::reset, 0.0});
  ImGui::Text("t = %.4f s   step %lld", st.time, static_cast<long long>(st.steps));
  ImGui::Text("speed %.3g sim s / wall s, %.0f steps/s%s", st.sim_s_per_wall_s, st.steps_per_s,
              st.stepping ? "" : " (when last running)");
  // In words a class understands: a simulated second shown in so many wall seconds.
  if (st.sim_s_per_wall_s > 0.0 && st.sim_s_per_wall_s < 0.95)
    ImGui::Text("slow motion x %.1f", 1.0 / st.sim_s_per_wall_s);
  else if (st.sim_s_per_wall_s >= 0.95 && st.sim_s_per_wall_s <= 1.05)
    ImGui::Text("real time");
  else if (st.sim_s_per_wall_s > 1.05)
    ImGui::Text("fast motion x %.1f", st.sim_s_per_wall_s);
  ImGui::Text("window %.1f frames/s", static_cast<double>(io.Framerate));
  if (!st.error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", st.error.c_str());

  // Gas.
  if (snap_ && snap_->has_gas()) {
    ImGui::Separator();
    ImGui::TextUnformatted("Gas");
    if (!ImGui::IsAnyItemActive()) velocity_ = static_cast<float>(st.superficial_velocity);
    // The slider's range is fixed from the scene's own velocity when the panel first shows it: a
    // range that followed the live value ran away under a held mouse button (each frame's new
    // velocity widened the range, which moved the value under the pointer again).
    if (velocity_top_ <= 0.0f)
      velocity_top_ = std::max(5.0f, 1.5f * static_cast<float>(st.superficial_velocity));
    if (ImGui::SliderFloat("U (m/s)", &velocity_, 0.0f, velocity_top_, "%.2f"))
      post({ViewCommand::Kind::velocity, static_cast<double>(velocity_)});
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Ctrl+click to type a velocity");
    ImGui::Text("jet %.1f m/s (fastest inlet face %.1f m/s)", st.jet_velocity,
                st.inlet_jet_velocity);
  }
  if (ImGui::Button(st.ideal ? "Back to the scene's contacts" : "Ideal case (eta = 0, gamma = 0)"))
    post({ViewCommand::Kind::ideal, st.ideal ? 0.0 : 1.0});
  if (st.ideal) ImGui::TextUnformatted("ideal: contact damping 0, friction 0");

  // Colours.
  ImGui::Separator();
  ImGui::TextUnformatted("Colour (c)");
  using render::ColourBy;
  const std::pair<ColourBy, const char*> modes[] = {{ColourBy::speed, "speed"},
                                                    {ColourBy::force, "force"},
                                                    {ColourBy::torque, "torque"},
                                                    {ColourBy::overlap, "overlap"},
                                                    {ColourBy::height, "mixing"}};
  for (std::size_t k = 0; k < std::size(modes); ++k) {
    if (k > 0) ImGui::SameLine();
    if (ImGui::RadioButton(modes[k].second, look_.colour_by == modes[k].first)) {
      look_.colour_by = modes[k].first;
      look_.range_min = look_.range_max = 0.0;
    }
  }
  if (snap_)
    colour_bar(render::colour_scale(look_.colour_by, *snap_, look_.range_min, look_.range_max,
                                    look_.height_bands));

  // Arrows and background.
  ImGui::Separator();
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
  ImGui::SameLine();
  if (ImGui::Checkbox("bubble outlines", &look_.bubble_outlines))
    post({ViewCommand::Kind::bubbles, look_.bubble_outlines ? 1.0 : 0.0});
  ImGui::SameLine();
  ImGui::Text("zoom %.1fx", view_.zoom);
  ImGui::SameLine();
  if (ImGui::SmallButton("1x")) view_ = {};

  // Plots.
  ImGui::Separator();
  draw_plots();

  // The picked particle.
  ImGui::Separator();
  if (tracked_ >= 0 && snap_) {
    draw_particle_info(static_cast<std::size_t>(tracked_), false);
    if (ImGui::SmallButton("stop tracking")) {
      tracked_ = -1;
      trajectory_.clear();
    }
  } else {
    ImGui::TextDisabled("hover a particle; click to track it");
  }

  // Pictures.
  ImGui::Separator();
  if (ImGui::Button("Screenshot")) screenshot_requests_.push_back(next_name("screenshot", ".png"));
  ImGui::SameLine();
  const bool recording = video_ || !record_dir_.empty();
  if (ImGui::Button(recording ? "Stop recording" : "Record")) {
    try {
      if (recording)
        stop_recording();
      else
        start_recording(next_name("recording", record_mp4_ ? ".mp4" : ""));
    } catch (const std::exception& e) {
      message_ = e.what();
    }
  }
  if (!recording) {
    ImGui::SameLine();
    if (ImGui::RadioButton("MP4", record_mp4_)) record_mp4_ = true;
    ImGui::SameLine();
    if (ImGui::RadioButton("PNG", !record_mp4_)) record_mp4_ = false;
  }
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  ImGui::Separator();
  ImGui::TextDisabled(
      "space run/pause, s step, r reset, c colour\nwheel zoom, drag pan, "
      "right double-click 1x");
  ImGui::End();
}

}  // namespace fluidbed::app
