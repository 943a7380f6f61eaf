#pragma once
// Text for frame labels: a TrueType font (assets/fonts/DejaVuSans.ttf) rasterised once per pixel
// size into an 8-bit coverage atlas (stb_truetype), and strings laid out as textured quads.
// UTF-8; covers printable ASCII, Latin-1 from the degree sign on (times sign, micro) and Greek.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fluidbed::render {

struct GlyphQuad {
  float x0, y0, x1, y1;  // px, y down
  float u0, v0, u1, v1;  // atlas coordinates in [0, 1]
};

class FontAtlas {
 public:
  // `ttf` is the font file's bytes (kept alive by the caller); `pixel_height` the em height in px.
  FontAtlas(const std::vector<unsigned char>& ttf, float pixel_height);
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
  struct Impl;
  std::unique_ptr<Impl> impl_;
  float pixel_height_;
  int atlas_size_ = 512;
  std::vector<std::uint8_t> atlas_;
  float ascent_ = 0.0f;
};

// The bytes of a font file; throws InputError naming the file when it cannot be read.
std::vector<unsigned char> read_font_file(const std::string& path);

}  // namespace fluidbed::render
