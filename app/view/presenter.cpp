// The presenter mode (`view --present`, the `p` key): for a class at the back of a room. The bed
// on the left at the window's full height with words where things are (the jet, bubbles, a slug,
// the dead zones, the freeboard: view/bed_labels.hpp); on the right, in text two to three times
// the panel's, the controls a demo needs (run, reset, Fig. 6 from the packed bed, the gas, the
// stages of Fig. 6, ideal spheres), what the bed is doing in words, and a large live Fig. 6. No
// symbols a class has not met: U and U_mf are said in words beside them, the contact model's eta
// and gamma, the CFL number and the overlap's "radii sum" are not shown (the full panel, `p`
// again, keeps them).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/text_format.hpp"
#include "view/bed_labels.hpp"
#include "view/presets.hpp"
#include "view/status_words.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

std::string fmt(const char* f, double a) {
  return format_number(f, a);
}

// A button on the current row when it fits there, else on the next.
bool flow_button(const char* label, bool first) {
  const ImGuiStyle& st = ImGui::GetStyle();
  const float w = ImGui::CalcTextSize(label).x + 2.0f * st.FramePadding.x;
  if (!first) {
    ImGui::SameLine();
    if (ImGui::GetContentRegionAvail().x < w) ImGui::NewLine();
  }
  return ImGui::Button(label);
}

}  // namespace

void Viewer::draw_presenter() {
  const ImGuiIO& io = ImGui::GetIO();
  const EngineStatus& st = status_;
  const float x0 = presenter_.bed_right;
  ImGui::SetNextWindowPos(ImVec2(x0, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(std::max(1.0f, io.DisplaySize.x - x0), io.DisplaySize.y),
                           ImGuiCond_Always);
  ImGui::Begin("presenter", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar);
  ImGui::PushFont(font_of(presenter_.font));

  // The controls.
  const char* run_label = bed_is_running() ? "Pause" : "Run";
  if (flow_button(run_label, true)) toggle_run();
  note_widget("present_run_button", run_label);
  if (flow_button("Reset", false)) post({ViewCommand::Kind::reset, 0.0});
  note_widget("present_reset_button");
  ImGui::SameLine();
  fig6_button(ImVec2(0.0f, 0.0f));
  ImGui::SameLine();
  ImGui::TextUnformatted("p: full panel");
  velocity_slider("gas velocity U = %.2f m/s");
  bool first = true;
  if (opt_.umf > 0.0)
    for (const Preset& p : kPresets) {
      const double u = p.umf_multiple * opt_.umf;
      char label[96];
      std::snprintf(label, sizeof label, "%s", p.label);
      if (flow_button(label, first)) set_velocity(u);
      first = false;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("U = %.2f m/s: %s", u, p.what);
      note_widget((std::string("present_preset_") + p.name).c_str(), fmt("%.6g", u));
    }
  if (flow_button(st.ideal ? "Real spheres again" : "Ideal spheres (bounce forever)", first))
    post({ViewCommand::Kind::ideal, st.ideal ? 0.0 : 1.0});
  ImGui::Separator();

  // What the bed is doing, in words.
  std::string gas = fmt("Gas velocity U = %.2f m/s", st.superficial_velocity);
  if (opt_.umf > 0.0)
    gas += fmt(" = %.2f U_mf", st.superficial_velocity / opt_.umf) +
           fmt(" (U_mf = %.2f m/s, the minimum fluidization velocity: the gas that just carries "
               "the bed's weight)",
               opt_.umf);
  ImGui::TextWrapped("%s", gas.c_str());
  note_widget("present_gas", gas);
  if (!plot_dp_.empty()) {
    const std::string dp = fmt("Pressure drop %.0f Pa", plot_dp_.back()) +
                           fmt("; the bed's weight per area %.0f Pa", st.curve.weight_per_area);
    ImGui::TextWrapped("%s", dp.c_str());
  }
  std::string doing = run_state_words(st, script_runs_the_bed());
  if (held_ && !st.stepping) doing = "paused";
  if (const auto& v = st.bubbles; v && snap_ && snap_->has_gas())
    doing = "The bed: " + regime_words(*v) + " (" + doing + ")";
  if (const std::string speed = speed_for_a_class(st.sim_s_per_wall_s); !speed.empty())
    doing += "; " + speed;
  ImGui::TextWrapped("%s", doing.c_str());
  note_widget("present_doing", doing);

  // The live Fig. 6 fills what is left above the messages' area (three lines at the foot).
  const float line = ImGui::GetTextLineHeightWithSpacing();
  const float messages = 3.0f * line + 2.0f * ImGui::GetStyle().WindowPadding.y;
  const float chart = ImGui::GetContentRegionAvail().y - messages - 3.2f * line;
  if (snap_ && snap_->has_gas() && chart > 4.0f * line) {
    draw_curve_plot(chart, true);
    std::string phase = describe_phase(st.curve);
    // Two U_mf on the screen, each said for what it is.
    if (st.curve.umf.ok && opt_.umf > 0.0)
      phase += fmt(". This curve's way down puts U_mf near %.2f m/s (rough: a few short points); ",
                   st.curve.umf.umf) +
               fmt("the stage buttons use %.2f m/s, ", opt_.umf) + opt_.umf_method_short + ".";
    ImGui::TextWrapped("%s", phase.c_str());
  }
  ImGui::BeginChild("present_messages", ImVec2(0.0f, 0.0f), true);
  draw_messages(true);
  ImGui::EndChild();
  ImGui::PopFont();
  ImGui::End();
}

// The presenter mode's words in the whole bed's panel, each on a dark patch so that it reads
// over any colour; a word that would cover another is left out.
void Viewer::draw_bed_labels() {
  if (!present_ || !snap_ || !status_.bubbles || layout_.beds.empty() || !snap_->has_gas()) return;
  const std::vector<BedLabel> labels = bed_labels(*snap_, *status_.bubbles);
  const render::BedView& bed = layout_.beds.front();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const render::Rect& c = bed.clip;
  const ImVec2 clip0(to_window_x(c.x0), to_window_y(c.y0)),
      clip1(to_window_x(c.x1), to_window_y(c.y1));
  dl->PushClipRect(clip0, clip1, true);
  ImFont* font = font_of(0.75f * presenter_.font);
  const float size = font->FontSize, pad = 0.2f * size;
  std::vector<std::pair<ImVec2, ImVec2>> drawn;
  std::string noted;
  for (const BedLabel& l : labels) {
    const ImVec2 text = font->CalcTextSizeA(size, 1e9f, 0.0f, l.text.c_str());
    const float cx = to_window_x(bed.px(l.x)), cy = to_window_y(bed.py(l.y));
    // Kept inside the bed's panel.
    const float left = std::clamp(cx - 0.5f * text.x, clip0.x + pad, clip1.x - text.x - pad);
    const float top = std::clamp(cy - 0.5f * text.y, clip0.y + pad, clip1.y - text.y - pad);
    const ImVec2 a(left - pad, top - pad), b(left + text.x + pad, top + text.y + pad);
    const bool covers = std::any_of(drawn.begin(), drawn.end(), [&](const auto& r) {
      return a.x < r.second.x && r.first.x < b.x && a.y < r.second.y && r.first.y < b.y;
    });
    if (covers) continue;
    drawn.emplace_back(a, b);
    dl->AddRectFilled(a, b, IM_COL32(20, 20, 28, 190), 0.3f * size);
    dl->AddText(font, size, ImVec2(left, top), IM_COL32(255, 255, 255, 255), l.text.c_str());
    noted += (noted.empty() ? "" : ",") + l.text;
  }
  dl->PopClipRect();
  if (!widgets_file_.empty()) {
    std::replace(noted.begin(), noted.end(), ' ', '_');
    widget_lines_.push_back("bed_labels " + fmt("%.1f", clip0.x) + " " + fmt("%.1f", clip0.y) +
                            " " + fmt("%.1f", clip1.x) + " " + fmt("%.1f", clip1.y) + " " +
                            (noted.empty() ? "none" : noted));
  }
}

}  // namespace fluidbed::app
