#pragma once
// Text for frame labels: a TrueType font (assets/fonts/DejaVuSans.ttf, read by
// render/font_file.hpp) rasterised once per pixel size into an 8-bit coverage atlas
// (stb_truetype), and strings laid out as textured quads. UTF-8; covers printable ASCII, Latin-1
// from the degree sign on (times sign, micro), Greek, superscript digits and signs, and the minus
// sign (the tick labels of render/ticks.hpp).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/font_file.hpp"

namespace fluidbed::render {

struct GlyphQuad {
  float x0, y0, x1, y1;  // px, y down
  float u0, v0, u1, v1;  // atlas coordinates in [0, 1]
};

// The code points every atlas holds (each must have a glyph in the font).
std::vector<int> atlas_code_points();

class FontAtlas {
 public:
  // `font` is kept alive by the caller; `pixel_height` the em height in px.
  FontAtlas(const FontFile& font, float pixel_height);
  ~FontAtlas();
  FontAtlas(const FontAtlas&) = delete;
  FontAtlas& operator=(const FontAtlas&) = delete;

  float pixel_height() const { return pixel_height_; }
  int atlas_size() const { return atlas_size_; }  // square, one byte per texel
  const std::vector<std::uint8_t>& atlas() const { return atlas_; }
  float ascent() const { return ascent_; }  // px above the baseline (capitals and digits)

  // Quads of `text` with its baseline starting at (x, y) (px, y down); unknown characters skip.
  void layout(const std::string& text, float x, float y, std::vector<GlyphQuad>& out) const;
  float advance(const std::string& text) const;  // px

 private:
  // Places each glyph of `text` from the pen at (x, y), px; returns the pen's x at the end.
  template <class F>
  float walk(const std::string& text, float x, float y, F&& each) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  float pixel_height_;
  int atlas_size_ = 512;
  std::vector<std::uint8_t> atlas_;
  float ascent_ = 0.0f;
};

}  // namespace fluidbed::render
