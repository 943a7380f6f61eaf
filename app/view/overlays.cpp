// What the window draws over the bed's frame with ImGui (in screenshots and recordings too, which
// read the window back): the tracked particle's ring and path and the hovered particle's ring in
// every bed panel (the whole bed and the close-up, zoomed or not), the hovered bubble's outline,
// and the tooltip that names what is under the pointer.
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "view/window.hpp"

namespace fluidbed::app {

void Viewer::draw_overlays() {
  if (!snap_ || layout_.beds.empty()) return;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const bool tracking = tracked_ >= 0 && static_cast<std::size_t>(tracked_) < snap_->particles();
  for (const render::BedView& bed : layout_.beds) {
    const render::Rect& c = bed.clip;
    dl->PushClipRect(ImVec2(to_window_x(c.x0), to_window_y(c.y0)),
                     ImVec2(to_window_x(c.x1), to_window_y(c.y1)), true);
    const auto at = [&](double x, double y) {
      return ImVec2(to_window_x(bed.px(x)), to_window_y(bed.py(y)));
    };
    const float px_per_m = static_cast<float>(bed.scale) / fb_scale_;
    if (tracking) {
      std::vector<ImVec2> pts;
      pts.reserve(trajectory_.size());
      for (const auto& [x, y] : trajectory_) pts.push_back(at(x, y));
      if (pts.size() > 1)
        dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), IM_COL32(220, 30, 30, 230), 0,
                        2.0f);
      const auto i = static_cast<std::size_t>(tracked_);
      dl->AddCircle(at(snap_->x[i], snap_->y[i]),
                    std::max(4.0f, static_cast<float>(snap_->radius[i]) * px_per_m + 2.0f),
                    IM_COL32(220, 30, 30, 255), 0, 2.5f);
    }
    if (hovered_) {
      const std::size_t i = *hovered_;
      dl->AddCircle(at(snap_->x[i], snap_->y[i]),
                    std::max(4.0f, static_cast<float>(snap_->radius[i]) * px_per_m + 1.5f),
                    IM_COL32(255, 255, 255, 255), 0, 2.0f);
    }
    if (hovered_bubble_ && status_.bubbles) {
      // The region's cells' outer edges, in yellow.
      const BubbleView& v = *status_.bubbles;
      const Bubble& b = *hovered_bubble_;
      const auto k = static_cast<int>(hovered_bubble_ - v.regions.data());
      const auto label = [&](int i, int j) {
        return i < 0 || j < 0 || i >= v.grid.nx || j >= v.grid.ny
                   ? kCellDense
                   : v.label[static_cast<std::size_t>(v.grid.index(i, j))];
      };
      const ImU32 yellow = IM_COL32(255, 225, 40, 255);
      for (int j = b.j_min; j <= b.j_max; ++j)
        for (int i = b.i_min; i <= b.i_max; ++i) {
          if (label(i, j) != k) continue;
          const double x0 = i * v.grid.dx, x1 = x0 + v.grid.dx, y0 = j * v.grid.dy,
                       y1 = y0 + v.grid.dy;
          if (label(i - 1, j) != k) dl->AddLine(at(x0, y0), at(x0, y1), yellow, 2.5f);
          if (label(i + 1, j) != k) dl->AddLine(at(x1, y0), at(x1, y1), yellow, 2.5f);
          if (label(i, j - 1) != k) dl->AddLine(at(x0, y0), at(x1, y0), yellow, 2.5f);
          if (label(i, j + 1) != k) dl->AddLine(at(x0, y1), at(x1, y1), yellow, 2.5f);
        }
    }
    dl->PopClipRect();
  }
  draw_bed_labels();
}

void Viewer::draw_hover_tooltip(const std::optional<std::size_t>& particle, const Bubble* bubble) {
  ImGui::BeginTooltip();
  if (bubble) {
    if (bubble->touches_jet) {
      ImGui::Text("the jet's cavity: %.0f mm across, %.0f mm high", 1000.0 * bubble->width,
                  1000.0 * bubble->height);
    } else {
      ImGui::Text("%s %d: size %.0f mm (equivalent diameter), %.0f x %.0f mm",
                  bubble->slug ? "slug" : "bubble", bubble->id, 1000.0 * bubble->d_eq,
                  1000.0 * bubble->width, 1000.0 * bubble->height);
      const BubbleView& v = *status_.bubbles;
      const auto k = static_cast<std::size_t>(bubble - v.regions.data());
      const RiseShown r =
          rise_shown(*bubble, k < v.frames_seen.size() ? v.frames_seen[k] : 0, v.min_track_frames);
      if (r.shown)
        ImGui::Text("rising at %.2f m/s (2D reference 0.5 sqrt(g D_e): %.2f m/s)", r.vy,
                    0.5 * std::sqrt(v.gravity * bubble->d_eq));
      else
        ImGui::TextDisabled("%s", r.words.c_str());
    }
    if (particle) ImGui::Separator();
  }
  if (particle) draw_particle_info(*particle, true);
  ImGui::EndTooltip();
}

}  // namespace fluidbed::app
