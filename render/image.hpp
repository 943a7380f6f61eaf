#pragma once
// An 8-bit RGB picture, rows from the top, and its PNG file (deflated by zlib).
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

// Writes `image` as PNG to `path` through a temporary file renamed into place, so a reader never
// sees half a frame. Throws std::runtime_error naming the file on failure.
void write_png(const std::string& path, const Image& image);

}  // namespace fluidbed::render
