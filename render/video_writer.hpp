#pragma once
// An MP4 made by Debian's ffmpeg from frames piped to it as raw RGB (no PNG files in between):
// H.264 (libx264), yuv420p so that every player opens it. The file appears under its name only
// when ffmpeg finished it.
#include <string>
#include <vector>

#include "render/image.hpp"

namespace fluidbed::render {

class VideoWriter {
 public:
  // Starts ffmpeg for `path`; frames are width x height (both even) shown at `fps`.
  // Throws InputError for an odd size, std::runtime_error when ffmpeg cannot start.
  VideoWriter(const std::string& path, int width, int height, double fps);
  ~VideoWriter();  // without close(): stops ffmpeg and leaves no file
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Sends one frame (of the size given above); throws when ffmpeg is gone.
  void write(const Image& frame);
  // Ends the stream, waits for ffmpeg and moves the file into place; throws if ffmpeg failed.
  void close();
  int frames() const { return frames_; }

 private:
  std::string path_, partial_;
  int width_, height_;
  int fd_ = -1;    // ffmpeg's standard input
  int pid_ = -1;
  int frames_ = 0;
};

// Joins MP4 files written by VideoWriter with the same size and rate into one at `path`, without
// encoding again (ffmpeg's concat demuxer, streams copied; one part is linked or copied). The
// parts stay (a run's checkpoint may still name them). Throws std::runtime_error when ffmpeg
// fails.
void join_videos(const std::vector<std::string>& parts, const std::string& path);

}  // namespace fluidbed::render
