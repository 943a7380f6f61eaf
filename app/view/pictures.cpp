// The viewer's pictures and files: screenshots and recordings of the window as shown (panel,
// bed, captions), the live curve saved, and the widgets' places for tests.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "render/image.hpp"
#include "view/curve_chart.hpp"
#include "view/window.hpp"

namespace fluidbed::app {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}
constexpr double kRecordFps = 25.0;  // frames per second of recordings (wall-clock time)

// The window as shown (the back buffer, after the panel was drawn), rows from the top.
render::Image read_window(const render::GlContext& context) {
  const auto& gl = context.gl();
  render::Image img;
  img.width = context.width();
  img.height = context.height();
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(img.width) *
                                 static_cast<std::size_t>(img.height) * 4);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  gl.ReadBuffer(GL_BACK);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  img.rgb.resize(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 3);
  for (int y = 0; y < img.height; ++y) {
    const std::uint8_t* src = rgba.data() + static_cast<std::size_t>(img.height - 1 - y) *
                                                static_cast<std::size_t>(img.width) * 4;
    std::uint8_t* dst =
        img.rgb.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) * 3;
    for (int x = 0; x < img.width; ++x, src += 4, dst += 3) {
      dst[0] = src[0];
      dst[1] = src[1];
      dst[2] = src[2];
    }
  }
  return img;
}

// `img` cut or padded (black) to w x h: a recording keeps the size it started with.
render::Image fit(const render::Image& img, int w, int h) {
  if (img.width == w && img.height == h) return img;
  render::Image out;
  out.width = w;
  out.height = h;
  out.rgb.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 0);
  for (int y = 0; y < std::min(h, img.height); ++y)
    std::copy_n(img.pixel(0, y), static_cast<std::size_t>(std::min(w, img.width)) * 3,
                out.rgb.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(w) * 3);
  return out;
}

}  // namespace

// Where the widgets and bed panels are, in window pixels (for tests that drive the window with
// a pointer, $FLUIDBED_VIEW_WIDGETS): one line each, "name x0 y0 x1 y1 value"; rewritten when
// something changed.
void Viewer::write_widgets() {
  std::string text;
  char line[160];
  const ImGuiIO& io = ImGui::GetIO();
  std::snprintf(line, sizeof line, "window 0 0 %.0f %.0f %d\n", io.DisplaySize.x, io.DisplaySize.y,
                static_cast<int>(panel_.font));
  text += line;
  for (std::size_t k = 0; k < layout_.beds.size(); ++k) {
    const render::Rect& c = layout_.beds[k].clip;
    std::snprintf(line, sizeof line, "bed%zu %.1f %.1f %.1f %.1f %s\n", k, to_window_x(c.x0),
                  to_window_y(c.y0), to_window_x(c.x1), to_window_y(c.y1),
                  layout_.beds[k].zoomed ? "zoomed" : "whole");
    text += line;
  }
  for (const std::string& w : widget_lines_) text += w + "\n";
  if (text == widgets_written_) return;
  widgets_written_ = text;
  try {
    write_file_atomically(widgets_file_, [&](std::ofstream& out) { out << text; });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fluidbed view: %s\n", e.what());
    widgets_file_.clear();
  }
}

std::string Viewer::next_name(const std::string& stem, const std::string& ext) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(opt_.out_dir, ec);
  for (;;) {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%03d%s", stem.c_str(), ++counter_, ext.c_str());
    const fs::path p = fs::path(opt_.out_dir) / name;
    if (!fs::exists(p, ec)) return p.string();
  }
}

void Viewer::capture_if_requested() {
  const bool recording = video_ || !record_dir_.empty();
  if (screenshot_requests_.empty() && !recording) return;
  if (!screenshot_requests_.empty() && settle_frames_ > 0) {
    --settle_frames_;
    if (!recording) return;
  }
  const render::Image img = read_window(*context_);
  if (!screenshot_requests_.empty() && settle_frames_ <= 0) {
    for (const std::string& path : screenshot_requests_)
      write_output(path, [&] { render::write_png(path, img); });
    screenshot_requests_.clear();
  }
  if (!recording) return;
  // Frames at a steady 25 per wall second: repeated when drawing is slower, skipped when faster,
  // so the video plays at the speed the class saw.
  const double elapsed = seconds_between(record_t0_, Clock::now());
  const int due = static_cast<int>(std::floor(elapsed * kRecordFps)) + 1;
  try {
    if (video_) {
      const render::Image f = fit(img, record_frames_w_, record_frames_h_);
      for (int n = 0; record_frames_ < due && n < 8; ++n, ++record_frames_) video_->write(f);
      record_frames_ = std::max(record_frames_, due);
    } else if (record_frames_ < due) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%06d.png", record_frames_);
      render::write_png((std::filesystem::path(record_dir_) / name).string(), img);
      record_frames_ = due;
    }
  } catch (const std::exception& e) {
    message_ = std::string("recording stopped: ") + e.what();
    video_.reset();
    record_dir_.clear();
  }
}

void Viewer::start_recording(const std::string& target) {
  stop_recording();
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool mp4 = fs::path(target).extension() == ".mp4";
  record_frames_ = 0;
  record_t0_ = Clock::now();
  record_target_ = target;
  if (mp4) {
    if (fs::path(target).has_parent_path())
      fs::create_directories(fs::path(target).parent_path(), ec);
    record_frames_w_ = context_->width() & ~1;
    record_frames_h_ = context_->height() & ~1;
    video_ = std::make_unique<render::VideoWriter>(target, record_frames_w_, record_frames_h_,
                                                   kRecordFps);
  } else {
    fs::create_directories(target, ec);
    if (ec) throw InputError("cannot create the recording folder " + target + ": " + ec.message());
    record_dir_ = target;
  }
  message_ = "recording to " + target;
}

void Viewer::stop_recording() {
  if (video_) {
    auto v = std::move(video_);
    v->close();
    message_ = "wrote " + record_target_ + " (" + std::to_string(v->frames()) + " frames)";
    std::printf("%s\n", message_.c_str());
  } else if (!record_dir_.empty()) {
    message_ = "wrote " + std::to_string(record_frames_) + " frames to " + record_dir_;
    std::printf("%s\n", message_.c_str());
    record_dir_.clear();
  }
}

void Viewer::save_curve_file(const std::string& path) {
  write_output(path, [&] { write_curve_file(path, status_.curve, opt_.font); });
}

// A file the viewer writes (its folder made first), said in the panel and on the terminal; a
// script stops at a failure to write (exit status 4).
void Viewer::write_output(const std::string& path, const std::function<void()>& write) {
  try {
    const auto parent = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    write();
    message_ = "wrote " + path;
    std::printf("wrote %s\n", path.c_str());
  } catch (const std::exception& e) {
    message_ = e.what();
    if (!opt_.script.empty()) {
      std::fprintf(stderr, "fluidbed: output failed: %s\n", e.what());
      exit_status_ = 4;
      quit_ = true;
    }
  }
}

}  // namespace fluidbed::app
