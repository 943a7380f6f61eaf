#include "render/font_file.hpp"

#include <stb_truetype.h>

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace fluidbed::render {

std::vector<std::string> font_search_paths(const std::string& asset_dir) {
  constexpr const char* kFile = "fonts/DejaVuSans.ttf";
  std::vector<std::string> paths;
  if (!asset_dir.empty()) paths.push_back(asset_dir + "/" + kFile);
  paths.emplace_back("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
  return paths;
}

FontFile load_font(const std::vector<std::string>& paths) {
  std::string tried;
  for (const std::string& path : paths) {
    if (!tried.empty()) tried += ", ";
    tried += path;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      tried += " (missing)";
      continue;
    }
    FontFile f;
    f.path = path;
    f.bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    // 12 bytes: a TrueType file's offset table, which stb reads before checking anything.
    f.offset = f.bytes.size() < 12 ? -1 : stbtt_GetFontOffsetForIndex(f.bytes.data(), 0);
    stbtt_fontinfo info;
    if (f.offset < 0 || stbtt_InitFont(&info, f.bytes.data(), f.offset) == 0) {
      tried += " (not a TrueType font)";
      continue;
    }
    return f;
  }
  throw std::runtime_error("no usable font; tried " + tried);
}

int next_code_point(std::string_view s, std::size_t& i) {
  const auto byte = [&s](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i++);
  if (c < 0x80) return c;
  int extra = 0;
  int cp = 0;
  if ((c & 0xE0) == 0xC0) {
    extra = 1;
    cp = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    extra = 2;
    cp = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    extra = 3;
    cp = c & 0x07;
  } else {
    return 0xFFFD;
  }
  for (int k = 0; k < extra; ++k) {
    if (i >= s.size() || (byte(i) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (byte(i++) & 0x3F);
  }
  return cp;
}

}  // namespace fluidbed::render
