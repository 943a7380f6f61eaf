// A second bed beside the first: `view A.toml --beside B.toml`, or the panel's "Compare with the
// ideal twin" (the scene with contact damping and friction 0, from the packed bed, started with
// the first bed reset beside it). Each bed has its own engine thread, picture, dp and live curve;
// run, pause, step, reset, the gas and the curve's times act on both (Viewer::post), the ideal
// case and the stiffness on the first only. On two cores the two engines share them: each runs
// at about half the speed of one alone, and the panel shows both speeds.
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "core/text_format.hpp"
#include "view/status_words.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

constexpr std::size_t kBesidePoints = 4000;  // dp samples kept, as the first bed's

std::string fmt(const char* f, double a) {
  return format_number(f, a);
}

}  // namespace

void Viewer::toggle_twin() {
  if (own_twin_) {
    beside_ = nullptr;
    own_twin_.reset();  // stops its thread
    beside_snap_.reset();
    beside_status_ = {};
    beside_t_.clear();
    beside_dp_.clear();
    say("The ideal twin is closed.");
    return;
  }
  if (beside_) return;  // a --beside bed is there already
  if (script_runs_the_bed() || held_) {  // it would reset the bed under the lesson
    say("The ideal twin opens once the lesson or script has ended.");
    return;
  }
  ViewEngine::Options eo = engine_.options();
  eo.start_running = false;
  try {
    own_twin_ = std::make_unique<ViewEngine>(opt_.scene, eo);
  } catch (const std::exception& e) {
    say(std::string("The ideal twin could not start: ") + e.what());
    return;
  }
  // Both from the packed bed at the velocity the slider holds, the twin ideal, both running; the
  // twin of the particles in use (the panel may have changed them).
  if (status_.particle_diameter != opt_.scene.particles.diameter ||
      status_.particle_density != opt_.scene.particles.density)
    own_twin_->post(
        {ViewCommand::Kind::particles, status_.particle_diameter, status_.particle_density});
  own_twin_->post({ViewCommand::Kind::velocity, status_.superficial_velocity});
  own_twin_->post({ViewCommand::Kind::ideal, 1.0});
  own_twin_->start();
  beside_ = own_twin_.get();
  beside_name_ = "ideal twin (damping 0, friction 0)";
  const bool running = bed_is_running();
  post({ViewCommand::Kind::reset, 0.0});
  if (running) post({ViewCommand::Kind::run, 0.0});
  say("Both beds start again from the packed bed; the right one is ideal.");
}

void Viewer::take_beside() {
  if (!beside_) return;
  const EngineStatus st = beside_->status();
  if (st.generation != beside_generation_) {
    beside_generation_ = st.generation;
    beside_t_.clear();
    beside_dp_.clear();
  }
  for (const PlotSample& p : beside_->take_samples()) {
    beside_t_.push_back(static_cast<float>(p.t));
    beside_dp_.push_back(static_cast<float>(p.dp));
  }
  if (beside_t_.size() > kBesidePoints + kBesidePoints / 4) {
    const auto cut = static_cast<std::ptrdiff_t>(beside_t_.size() - kBesidePoints);
    beside_t_.erase(beside_t_.begin(), beside_t_.begin() + cut);
    beside_dp_.erase(beside_dp_.begin(), beside_dp_.begin() + cut);
  }
  beside_status_ = st;
  std::uint64_t seq = 0;
  if (auto s = beside_->snapshots().latest(&seq)) beside_snap_ = std::move(s);
}

// Its frame in the right half of the bed area, captioned with its name and its regime over it.
void Viewer::draw_beside_frame() {
  if (!beside_ || !beside_snap_ || beside_w_ <= 0) return;
  render::RenderSettings look = look_;
  look.close_up = 0.0;
  look.zoom = {};
  look.caption = beside_name_;
  look.bed_label = beside_status_.bubbles && beside_snap_->has_gas()
                       ? regime_words(*beside_status_.bubbles)
                       : "";
  renderer_->draw_frame(*beside_snap_, look, beside_w_, frame_h_);
  const render::Rect src{0.0f, 0.0f, static_cast<float>(beside_w_), static_cast<float>(frame_h_)};
  const render::Rect dst{beside_area_.x0 * fb_scale_, beside_area_.y0 * fb_scale_,
                         beside_area_.x0 * fb_scale_ + static_cast<float>(beside_w_),
                         beside_area_.y0 * fb_scale_ + static_cast<float>(frame_h_)};
  renderer_->blit_region_to_default(src, dst, context_->height());
}

// The panel's words on the bed beside, and the button for the ideal twin.
void Viewer::draw_beside_section() {
  if (!beside_ || own_twin_) {
    if (ImGui::Button(own_twin_ ? "Close the ideal twin" : "Compare with the ideal twin",
                      ImVec2(-1.0f, 0.0f)))
      toggle_twin();
    if (ImGui::IsItemHovered() && !own_twin_)
      ImGui::SetTooltip(
          "The same bed with ideal contacts beside this one, both from the packed "
          "bed at this velocity; the two share the cores");
    note_widget("twin_button", own_twin_ ? "open" : "closed");
  }
  if (!beside_) return;
  const EngineStatus& b = beside_status_;
  ImGui::TextWrapped("Beside: %s", beside_name_.c_str());
  std::string line = fmt("t = %.3f s", b.time) + fmt(", U = %.2f m/s", b.superficial_velocity);
  if (!beside_dp_.empty()) line += fmt(", dp now %.0f Pa", beside_dp_.back());
  if (b.bubbles && beside_snap_ && beside_snap_->has_gas()) line += ", " + regime_words(*b.bubbles);
  ImGui::TextWrapped("%s", line.c_str());
  note_widget("beside", fmt("%.9g", b.time));
  if (!b.error.empty()) ImGui::TextWrapped("It stopped: %s", b.error.c_str());
  ImGui::TextWrapped("%s", ("This bed " + speed_words(status_.sim_s_per_wall_s) + "; beside " +
                            speed_words(b.sim_s_per_wall_s) +
                            ". Two beds share the cores: each runs at about half the speed of "
                            "one alone.")
                               .c_str());
}

}  // namespace fluidbed::app
