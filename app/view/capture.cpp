#include "view/capture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <utility>

#include "core/errors.hpp"

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

WindowCapture::WindowCapture(std::function<void(const std::string&)> say)
    : say_(std::move(say)) {}

void WindowCapture::screenshot(const std::string& path) {
  screenshots_.push_back(path);
}

void WindowCapture::after_frame(
    const render::GlContext& context,
    const std::function<void(const std::string&, const render::Image&)>& write_screenshot) {
  const bool recording = this->recording();
  if (screenshots_.empty() && !recording) return;
  if (!screenshots_.empty() && settle_frames_ > 0) {
    --settle_frames_;
    if (!recording) return;
  }
  const render::Image img = read_window(context);
  if (!screenshots_.empty() && settle_frames_ <= 0) {
    for (const std::string& path : screenshots_) write_screenshot(path, img);
    screenshots_.clear();
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
    say_(std::string("recording stopped: ") + e.what());
    video_.reset();
    record_dir_.clear();
  }
}

void WindowCapture::start_recording(const std::string& target, int width, int height) {
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
    record_frames_w_ = width & ~1;
    record_frames_h_ = height & ~1;
    video_ = std::make_unique<render::VideoWriter>(target, record_frames_w_, record_frames_h_,
                                                   kRecordFps);
  } else {
    fs::create_directories(target, ec);
    if (ec) throw InputError("cannot create the recording folder " + target + ": " + ec.message());
    record_dir_ = target;
  }
  say_("recording to " + target);
}

void WindowCapture::stop_recording() {
  std::string said;
  if (video_) {
    auto v = std::move(video_);
    v->close();
    said = "wrote " + record_target_ + " (" + std::to_string(v->frames()) + " frames)";
  } else if (!record_dir_.empty()) {
    said = "wrote " + std::to_string(record_frames_) + " frames to " + record_dir_;
    record_dir_.clear();
  } else {
    return;
  }
  say_(said);
  std::printf("%s\n", said.c_str());
}

}  // namespace fluidbed::app
