#include "render/font.hpp"

#include <stb_truetype.h>

#include <stdexcept>

namespace fluidbed::render {
namespace {

struct Range {
  int first, count;
};
// Printable ASCII; Latin-1 from the degree sign on (signs, multiplication sign, letters); Greek
// without U+03A2 (no character); superscript zero, four to nine and signs (U+2070, U+2074-207B;
// one, two and three are Latin-1's) and the minus sign (U+2212) of tick labels. Every code point
// must be one the font has: stb_truetype (v1.26) gives a missing one the box of the first missing
// one by its index in another range, read past the end of a shorter range's glyphs (ASan: a
// SEGV when the window loaded larger panel fonts and the heap moved).
constexpr Range kRanges[] = {{32, 95},    {0xB0, 80},  {0x391, 17}, {0x3A3, 39},
                             {0x2070, 1}, {0x2074, 8}, {0x2212, 1}};

}  // namespace

std::vector<int> atlas_code_points() {
  std::vector<int> cps;
  for (const Range& r : kRanges)
    for (int k = 0; k < r.count; ++k) cps.push_back(r.first + k);
  return cps;
}

struct FontAtlas::Impl {
  std::vector<stbtt_packedchar> chars[std::size(kRanges)];

  const stbtt_packedchar* find(int cp, int& index) const {
    for (std::size_t r = 0; r < std::size(kRanges); ++r) {
      if (cp >= kRanges[r].first && cp < kRanges[r].first + kRanges[r].count) {
        index = cp - kRanges[r].first;
        return chars[r].data();
      }
    }
    return nullptr;
  }
};

FontAtlas::FontAtlas(const FontFile& font, float pixel_height)
    : impl_(std::make_unique<Impl>()), pixel_height_(pixel_height) {
  // Two-times horizontal oversampling keeps small labels crisp under sub-pixel placement; the
  // atlas grows until everything fits.
  for (atlas_size_ = 256; atlas_size_ <= 4096; atlas_size_ *= 2) {
    atlas_.assign(static_cast<std::size_t>(atlas_size_) * static_cast<std::size_t>(atlas_size_), 0);
    stbtt_pack_context pc;
    if (!stbtt_PackBegin(&pc, atlas_.data(), atlas_size_, atlas_size_, 0, 1, nullptr))
      throw std::runtime_error("font: stb_truetype could not start packing");
    stbtt_PackSetOversampling(&pc, 2, 1);
    stbtt_pack_range ranges[std::size(kRanges)];
    for (std::size_t r = 0; r < std::size(kRanges); ++r) {
      impl_->chars[r].assign(static_cast<std::size_t>(kRanges[r].count), stbtt_packedchar{});
      ranges[r] = stbtt_pack_range{};
      ranges[r].font_size = pixel_height;
      ranges[r].first_unicode_codepoint_in_range = kRanges[r].first;
      ranges[r].num_chars = kRanges[r].count;
      ranges[r].chardata_for_range = impl_->chars[r].data();
    }
    const int ok = stbtt_PackFontRanges(&pc, font.bytes.data(), 0, ranges, static_cast<int>(std::size(ranges)));
    stbtt_PackEnd(&pc);
    if (ok) break;
  }
  if (atlas_size_ > 4096) throw std::runtime_error("font: glyphs do not fit a 4096 px atlas");
  stbtt_fontinfo info;
  if (!stbtt_InitFont(&info, font.bytes.data(), font.offset))
    throw std::runtime_error("font: not a TrueType font: " + font.path);
  int x0, y0, x1, y1;
  stbtt_GetCodepointBox(&info, 'H', &x0, &y0, &x1, &y1);
  ascent_ = static_cast<float>(y1) * stbtt_ScaleForPixelHeight(&info, pixel_height);
}

FontAtlas::~FontAtlas() = default;

template <class F>
float FontAtlas::walk(const std::string& text, float x, float y, F&& each) const {
  for (std::size_t i = 0; i < text.size();) {
    int index = 0;
    const stbtt_packedchar* chars = impl_->find(next_code_point(text, i), index);
    if (!chars) continue;
    stbtt_aligned_quad q;
    stbtt_GetPackedQuad(chars, atlas_size_, atlas_size_, index, &x, &y, &q, 0);
    each(q);
  }
  return x;
}

void FontAtlas::layout(const std::string& text, float x, float y,
                       std::vector<GlyphQuad>& out) const {
  walk(text, x, y, [&out](const stbtt_aligned_quad& q) {
    if (q.x1 > q.x0) out.push_back({q.x0, q.y0, q.x1, q.y1, q.s0, q.t0, q.s1, q.t1});
  });
}

float FontAtlas::advance(const std::string& text) const {
  return walk(text, 0.0f, 0.0f, [](const stbtt_aligned_quad&) {});
}

}  // namespace fluidbed::render
