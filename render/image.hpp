#pragma once
// An 8-bit RGB picture, rows from the top, and its PNG file (deflated by zlib): the program's one
// PNG writer, for frames, screenshots and the charts (app/chart). No GL.
#include <cstdint>
#include <string>
#include <vector>

namespace fluidbed::render {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3, row 0 at the top

  const std::uint8_t* pixel(int x, int y) const {
    return rgb.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                         static_cast<std::size_t>(x)) * 3;
  }
};

// WIDTH x HEIGHT pixels of RGB (rows from the top, 3 bytes a pixel) as the bytes of a PNG file.
std::vector<std::uint8_t> encode_png(int width, int height, const std::uint8_t* rgb);
// Writes them to `path` through a temporary file of this process's own beside it, renamed into
// place, so a reader never sees half a picture and a failed write leaves nothing behind. Throws
// std::runtime_error naming the file on failure.
void write_png(const std::string& path, int width, int height, const std::uint8_t* rgb);
void write_png(const std::string& path, const Image& image);

}  // namespace fluidbed::render
