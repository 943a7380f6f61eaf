// The panel's plots, drawn with ImGui's draw lists on axes with ticks (render/ticks.hpp, the
// charts' algorithm): dp and the largest overlap against time (ranges robust to the start-up
// spike), and the live Fig. 6 (dp against U by branch, the bed's weight per area, U_mf).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/ticks.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

// A plot box with ticked and labelled axes, taking the panel's width and `height` px; maps data
// to screen.
struct Axes {
  ImVec2 p0, p1;  // the plot area (inside the axes)
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  ImVec2 at(double x, double y) const {
    const double tx = (x - x0) / (x1 - x0), ty = (y - y0) / (y1 - y0);
    return {p0.x + static_cast<float>(std::clamp(tx, 0.0, 1.0)) * (p1.x - p0.x),
            p1.y - static_cast<float>(std::clamp(ty, 0.0, 1.0)) * (p1.y - p0.y)};
  }
};

const ImU32 kAxis = IM_COL32(150, 150, 160, 255), kGrid = IM_COL32(70, 70, 80, 255),
            kLabel = IM_COL32(200, 200, 205, 255);

Axes axes(float height, double x0, double x1, double y0, double y1, const char* x_title,
          const char* y_title) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float fs = ImGui::GetFontSize();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  const render::Ticks yt = render::linear_ticks(y0, y1, 4), xt = render::linear_ticks(x0, x1, 5);
  float label_w = 0.0f;
  for (const std::string& l : yt.labels)
    label_w = std::max(label_w, ImGui::CalcTextSize(l.c_str()).x);
  Axes a;
  a.x0 = x0;
  a.x1 = x1;
  a.y0 = y0;
  a.y1 = y1;
  a.p0 = ImVec2(origin.x + label_w + 0.5f * fs, origin.y + 1.2f * fs);
  a.p1 = ImVec2(origin.x + width - 0.5f * fs, origin.y + height - 1.3f * fs);
  dl->AddRectFilled(a.p0, a.p1, IM_COL32(28, 30, 38, 255));
  // The y title over the axis, the x title right of the x labels' row.
  std::string yt_text = y_title;
  if (!yt.multiplier.empty()) yt_text += "  " + yt.multiplier;
  dl->AddText(ImVec2(origin.x, origin.y), kLabel, yt_text.c_str());
  for (std::size_t k = 0; k < yt.major.size(); ++k) {
    const float y = a.at(x0, yt.major[k]).y;
    dl->AddLine(ImVec2(a.p0.x, y), ImVec2(a.p1.x, y), kGrid);
    const float w = ImGui::CalcTextSize(yt.labels[k].c_str()).x;
    dl->AddText(ImVec2(a.p0.x - w - 0.25f * fs, y - 0.5f * fs), kLabel, yt.labels[k].c_str());
  }
  float last_right = -1e9f;
  for (std::size_t k = 0; k < xt.major.size(); ++k) {
    const float x = a.at(xt.major[k], y0).x;
    dl->AddLine(ImVec2(x, a.p1.y), ImVec2(x, a.p1.y + 0.3f * fs), kAxis);
    const float w = ImGui::CalcTextSize(xt.labels[k].c_str()).x;
    if (x - 0.5f * w < last_right + 0.3f * fs) continue;  // no overlapping labels
    dl->AddText(ImVec2(x - 0.5f * w, a.p1.y + 0.25f * fs), kLabel, xt.labels[k].c_str());
    last_right = x + 0.5f * w;
  }
  const float tw = ImGui::CalcTextSize(x_title).x;
  dl->AddText(ImVec2(a.p1.x - tw, origin.y), kLabel, x_title);
  dl->AddRect(a.p0, a.p1, kAxis);
  ImGui::Dummy(ImVec2(width, height));
  return a;
}

// The line through (x, y), at most two points per pixel column: the first and last of a column
// and its lowest and highest, in order of x. Thousands of samples over a few hundred columns drew
// thousands of anti-aliased segments each frame and halved the window's frame rate under
// software GL; the columns' extremes draw the same picture.
void series(ImDrawList* dl, const Axes& a, const std::vector<float>& x, const std::vector<float>& y,
            ImU32 colour) {
  std::vector<ImVec2> pts;
  const std::size_t n = std::min(x.size(), y.size());
  pts.reserve(std::min<std::size_t>(n, 4 * static_cast<std::size_t>(a.p1.x - a.p0.x + 2.0f)));
  std::size_t k = 0;
  while (k < n) {
    const float column = std::floor(a.at(x[k], y[k]).x);
    std::size_t lo = k, hi = k, j = k + 1;  // screen y grows downwards: lo has the largest
    for (; j < n; ++j) {
      const ImVec2 p = a.at(x[j], y[j]);
      if (std::floor(p.x) != column) break;
      if (p.y > a.at(x[lo], y[lo]).y) lo = j;
      if (p.y < a.at(x[hi], y[hi]).y) hi = j;
    }
    std::size_t keep[4] = {k, lo, hi, j - 1};
    std::sort(keep, keep + 4);
    for (std::size_t q = 0; q < 4; ++q)
      if (q == 0 || keep[q] != keep[q - 1]) pts.push_back(a.at(x[keep[q]], y[keep[q]]));
    k = j;
  }
  dl->PushClipRect(a.p0, a.p1, true);
  if (pts.size() > 1) dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), colour, 0, 1.5f);
  dl->PopClipRect();
}

void hline(ImDrawList* dl, const Axes& a, double y, ImU32 colour, const char* text) {
  if (!(y > a.y0 && y < a.y1)) return;
  const ImVec2 l = a.at(a.x0, y), r = a.at(a.x1, y);
  for (float x = l.x; x < r.x; x += 8.0f)
    dl->AddLine(ImVec2(x, l.y), ImVec2(std::min(x + 4.0f, r.x), l.y), colour, 1.5f);
  const ImVec2 size = ImGui::CalcTextSize(text);
  dl->AddText(ImVec2(r.x - size.x - 2.0f, l.y - size.y), colour, text);
}

}  // namespace

void Viewer::draw_plots() {
  const std::size_t n = plot_t_.size();
  if (n < 2) {
    ImGui::TextDisabled("(the plots start when the bed runs)");
    return;
  }
  const float h = 7.5f * ImGui::GetFontSize();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  // dp: a range that the start-up spike (or any short surge) does not set.
  auto [lo, hi] = robust_range(plot_dp_);
  const double wa = status_.curve.weight_per_area;
  ImGui::Text("dp now %.0f Pa (range shown %.0f to %.0f Pa)", plot_dp_.back(), lo, hi);
  const Axes d = axes(h, plot_t_.front(), plot_t_.back(), lo, hi, "t (s)", "dp (Pa)");
  hline(dl, d, wa, IM_COL32(200, 200, 120, 255), "W/A");
  series(dl, d, plot_t_, plot_dp_, IM_COL32(120, 190, 255, 255));
  if (beside_ && beside_t_.size() > 1)  // the bed beside, fainter, on the same axes
    series(dl, d, beside_t_, beside_dp_, IM_COL32(230, 230, 235, 150));
  note_widget("dp_plot", std::to_string(lo) + " " + std::to_string(hi));
  // The largest overlap: from 0, its top set robustly too.
  std::vector<float> percent(plot_overlap_.size());
  std::transform(plot_overlap_.begin(), plot_overlap_.end(), percent.begin(),
                 [](float v) { return 100.0f * v; });
  const double top = std::max(robust_range(percent, 0.01, 0.15).second, 0.5);
  ImGui::Text("largest overlap now %.2f %% of the radii sum", static_cast<double>(percent.back()));
  const Axes o = axes(h, plot_t_.front(), plot_t_.back(), 0.0, top, "t (s)", "overlap (%)");
  series(dl, o, plot_t_, percent, IM_COL32(255, 170, 110, 255));
}

void Viewer::draw_curve_plot(float height, bool for_a_class) {
  const CurveState& c = status_.curve;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  // Velocities from 0 to the slider's top; dp from 0 to a little above the weight or the data.
  double dp_top = 1.3 * c.weight_per_area;
  for (const CurveBranch& b : c.branches)
    for (const CurvePoint& p : b.points) dp_top = std::max(dp_top, 1.1 * (p.dp_mean + p.dp_std));
  const Axes a = axes(height, 0.0, velocity_top_, 0.0, std::max(dp_top, 1.0),
                      for_a_class ? "gas velocity U (m/s)" : "U (m/s)",
                      for_a_class ? "pressure drop (Pa)" : "mean dp (Pa)");
  hline(dl, a, c.weight_per_area, IM_COL32(200, 200, 120, 255),
        for_a_class ? "the bed's weight per area" : "W/A");
  const ImU32 up = IM_COL32(110, 190, 255, 255), down = IM_COL32(255, 150, 90, 255);
  // The bed beside: its points in grey crosses under this bed's.
  if (beside_) {
    dl->PushClipRect(a.p0, a.p1, true);
    const float r = 0.22f * ImGui::GetFontSize();
    for (const CurveBranch& b : beside_status_.curve.branches)
      for (const CurvePoint& p : b.points) {
        const ImVec2 q = a.at(p.u, p.dp_mean);
        const ImU32 grey = IM_COL32(225, 225, 230, 170);
        dl->AddLine(ImVec2(q.x - r, q.y - r), ImVec2(q.x + r, q.y + r), grey, 1.5f);
        dl->AddLine(ImVec2(q.x - r, q.y + r), ImVec2(q.x + r, q.y - r), grey, 1.5f);
      }
    dl->PopClipRect();
  }
  dl->PushClipRect(a.p0, a.p1, true);
  if (c.umf.ok) {  // the fit: the defluidization line up to U_mf, the plateau beyond
    const ImU32 fit = IM_COL32(255, 220, 120, 200);
    dl->AddLine(a.at(0.0, c.umf.intercept), a.at(c.umf.umf, c.umf.plateau), fit, 1.0f);
    dl->AddLine(a.at(c.umf.umf, c.umf.plateau), a.at(velocity_top_, c.umf.plateau), fit, 1.0f);
    const ImVec2 top = a.at(c.umf.umf, a.y1), bottom = a.at(c.umf.umf, a.y0);
    for (float y = top.y; y < bottom.y; y += 7.0f)
      dl->AddLine(ImVec2(top.x, y), ImVec2(top.x, std::min(y + 4.0f, bottom.y)), fit, 1.5f);
  }
  const float r = 0.22f * ImGui::GetFontSize();
  for (const CurveBranch& b : c.branches) {
    const ImU32 col = b.increasing ? up : down;
    std::vector<ImVec2> pts;
    for (const CurvePoint& p : b.points) pts.push_back(a.at(p.u, p.dp_mean));
    if (pts.size() > 1) dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), col, 0, 1.5f);
    for (const ImVec2& q : pts) {
      if (b.increasing)
        dl->AddCircleFilled(q, r, col);
      else
        dl->AddRect(ImVec2(q.x - r, q.y - r), ImVec2(q.x + r, q.y + r), col, 0.0f, 0, 1.5f);
    }
  }
  // The velocity now, and where its point will go.
  const ImVec2 now_top = a.at(c.held_u, a.y1), now_bottom = a.at(c.held_u, a.y0);
  dl->AddLine(now_top, now_bottom, IM_COL32(200, 200, 205, 90), 1.0f);
  dl->PopClipRect();
  if (c.umf.ok) {
    char text[48];
    std::snprintf(text, sizeof text, for_a_class ? "U_mf %.2f (rough)" : "U_mf %.2f", c.umf.umf);
    dl->AddText(ImVec2(a.at(c.umf.umf, a.y1).x + 3.0f, a.p0.y + 2.0f), IM_COL32(255, 220, 120, 255),
                text);
  }
  // The legend.
  ImGui::TextColored(ImVec4(0.43f, 0.75f, 1.0f, 1.0f),
                     for_a_class ? "o gas raised" : "o increasing U");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(1.0f, 0.59f, 0.35f, 1.0f),
                     for_a_class ? "[] gas lowered" : "[] decreasing U");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(0.78f, 0.78f, 0.47f, 1.0f),
                     for_a_class ? "-- weight %.0f Pa" : "-- W/A %.0f Pa", c.weight_per_area);
  if (beside_) ImGui::TextColored(ImVec4(0.88f, 0.88f, 0.9f, 1.0f), "x the bed beside");
  int points = 0;
  for (const CurveBranch& b : c.branches)
    for (const CurvePoint& p : b.points) points += p.shared ? 0 : 1;
  note_widget(
      for_a_class ? "present_curve" : "curve",
      std::to_string(points) + " points, " + std::to_string(c.branches.size()) + " branches");
}

}  // namespace fluidbed::app
