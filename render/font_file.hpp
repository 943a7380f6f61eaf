#pragma once
// Font files and UTF-8 text, for both users of stb_truetype: the frames' glyph atlas
// (render/font.hpp) and the charts' text (app/chart/text.cpp). No GL.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace fluidbed::render {

// A TrueType font file read into memory and checked to be one.
struct FontFile {
  std::string path;
  std::vector<unsigned char> bytes;
  int offset = 0;  // bytes to the file's first font (stbtt_GetFontOffsetForIndex)
};

// Where the font is looked for, in order: ASSET_DIR/fonts/DejaVuSans.ttf (when not empty; the
// program passes render/asset_dir.hpp's asset_dir(), which honours $FLUIDBED_ASSETS), then the
// Debian package's copy.
std::vector<std::string> font_search_paths(const std::string& asset_dir);

// The first of PATHS that reads as a TrueType font; std::runtime_error naming every path tried
// and why it was passed over (missing, not a TrueType font), on one line.
FontFile load_font(const std::vector<std::string>& paths);

// The code point of UTF-8 text at s[i], advancing i past it; a malformed sequence reads as
// U+FFFD and advances past what was read of it.
int next_code_point(std::string_view s, std::size_t& i);

}  // namespace fluidbed::render
