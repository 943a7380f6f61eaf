#pragma once
// The window's pictures of itself: screenshots of the window as shown (panel, bed, captions) and
// recordings of it (an MP4, or PNG frames in a folder) at a steady 25 frames per wall second,
// read back from the back buffer after each frame was drawn. The window (view/window.hpp) asks
// for them and says what was written; this side knows nothing of the panel or the engine.
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/video_writer.hpp"

namespace fluidbed::app {

class WindowCapture {
 public:
  // `say`: a line for the panel (a recording started, written, or stopped by a failure).
  explicit WindowCapture(std::function<void(const std::string&)> say);

  // A screenshot to `path`, written after the frame being drawn (or, while frames are being let
  // settle, after them).
  void screenshot(const std::string& path);
  // The screenshots wait until `frames` more frames were drawn: ImGui lays a changed panel out
  // over a frame or two.
  void settle(int frames) { settle_frames_ = frames; }
  bool screenshot_pending() const { return !screenshots_.empty(); }

  // Records the window into `target`: an .mp4 of `width` x `height` px (the window's size at the
  // start, made even; later frames are cut or padded to it), or PNG frames into the folder
  // `target`. A recording under way is stopped first. InputError when the folder cannot be made.
  void start_recording(const std::string& target, int width, int height);
  // Finishes the recording under way, if any (the MP4 closed), and says what it wrote.
  void stop_recording();
  bool recording() const { return video_ || !record_dir_.empty(); }

  // After a frame was drawn into `context`'s back buffer: reads the window back when a
  // screenshot is due (each written by `write_screenshot`) or a recording is under way (frames
  // repeated or skipped to keep 25 a second; a failure to write stops the recording and says so).
  void after_frame(
      const render::GlContext& context,
      const std::function<void(const std::string& path, const render::Image& window)>&
          write_screenshot);

 private:
  std::function<void(const std::string&)> say_;
  std::vector<std::string> screenshots_;
  int settle_frames_ = 0;  // frames to draw before the screenshots
  std::unique_ptr<render::VideoWriter> video_;
  std::string record_dir_;  // PNG frames
  std::string record_target_;
  int record_frames_ = 0;
  int record_frames_w_ = 0, record_frames_h_ = 0;  // px, an MP4's fixed size (even)
  std::chrono::steady_clock::time_point record_t0_;
};

}  // namespace fluidbed::app
