// Fonts and text: loading DejaVu Sans, setting UTF-8 lines with kerning, drawing them.
#include "chart/text.hpp"

#include <stb_truetype.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render/font_file.hpp"

namespace fluidbed::chart {

struct Font::Data {
  render::FontFile file;
  stbtt_fontinfo info{};                    // points into file.bytes
  double ascent = 0, descent = 0, cap = 0;  // font units, descent positive
  double line = 1;  // font units of ascent + descent: a font of size s px scales by s / line
};

Font Font::load(const std::vector<std::string>& paths) {
  auto data = std::make_shared<Data>();
  data->file = render::load_font(paths);  // read and checked to be a TrueType font
  stbtt_InitFont(&data->info, data->file.bytes.data(), data->file.offset);
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&data->info, &ascent, &descent, &gap);
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  stbtt_GetCodepointBox(&data->info, 'H', &x0, &y0, &x1, &y1);
  data->ascent = ascent;
  data->descent = -descent;
  data->cap = y1 > 0 ? y1 : 0.7 * ascent;
  data->line = std::max(1, ascent - descent);
  return Font(std::move(data));
}

const std::string& Font::path() const {
  return data_->file.path;
}

}  // namespace fluidbed::chart

namespace fluidbed::chart::detail {

namespace {

constexpr int kQuarters = 4;  // glyphs are placed to a quarter pixel

}  // namespace

TextPainter::TextPainter(const Font& font) : font_(&font.data()) {}

double TextPainter::cap_height(double size) const {
  return font_->cap * size / font_->line;
}
double TextPainter::descent(double size) const {
  return font_->descent * size / font_->line;
}

std::vector<TextPainter::Placed> TextPainter::shape(std::string_view utf8, double size,
                                                    double* advance) const {
  const double scale = size / font_->line;
  std::vector<Placed> placed;
  double pen = 0.0;
  int previous = 0;
  for (std::size_t i = 0; i < utf8.size();) {
    const int index = stbtt_FindGlyphIndex(&font_->info, render::next_code_point(utf8, i));
    if (previous != 0) pen += scale * stbtt_GetGlyphKernAdvance(&font_->info, previous, index);
    placed.push_back({index, pen});
    int glyph_advance = 0, bearing = 0;
    stbtt_GetGlyphHMetrics(&font_->info, index, &glyph_advance, &bearing);
    pen += scale * glyph_advance;
    previous = index;
  }
  *advance = pen;
  return placed;
}

double TextPainter::width(std::string_view utf8, double size) const {
  double advance = 0.0;
  shape(utf8, size, &advance);
  return advance;
}

const TextPainter::Glyph& TextPainter::glyph(int index, double size, int quarter) {
  const auto key = std::make_tuple(std::lround(size * 64.0), index, quarter);
  auto found = cache_.find(key);
  if (found != cache_.end()) return found->second;
  const auto scale = static_cast<float>(size / font_->line);
  const float shift = static_cast<float>(quarter) / kQuarters;
  Glyph g;
  int x1 = 0, y1 = 0;
  stbtt_GetGlyphBitmapBoxSubpixel(&font_->info, index, scale, scale, shift, 0.0F, &g.x0, &g.y0, &x1,
                                  &y1);
  g.w = std::max(0, x1 - g.x0);
  g.h = std::max(0, y1 - g.y0);
  g.alpha.assign(static_cast<std::size_t>(g.w) * static_cast<std::size_t>(g.h), 0);
  if (g.w > 0 && g.h > 0) {
    stbtt_MakeGlyphBitmapSubpixel(&font_->info, g.alpha.data(), g.w, g.h, g.w, scale, scale, shift,
                                  0.0F, index);
  }
  return cache_.emplace(key, std::move(g)).first->second;
}

void TextPainter::origin(double advance, double size, Align align, Anchor anchor, int* u0,
                         int* base) const {
  const double along = align == Align::Start    ? 0.0
                       : align == Align::Centre ? -0.5 * advance
                                                : -advance;
  *u0 = static_cast<int>(std::lround(along));
  double across = 0.0;
  switch (anchor) {
    case Anchor::Top:
      across = cap_height(size);
      break;
    case Anchor::Middle:
      across = 0.5 * cap_height(size);
      break;
    case Anchor::Baseline:
      break;
    case Anchor::Bottom:
      across = -descent(size);
      break;
  }
  *base = static_cast<int>(std::lround(across));
}

Box TextPainter::bounds(std::string_view utf8, double x, double y, double size, Align align,
                        Anchor anchor, bool vertical) const {
  const double advance = width(utf8, size);
  int u0 = 0, base = 0;
  origin(advance, size, align, anchor, &u0, &base);
  const double ax = std::round(x), ay = std::round(y);
  // Accents and brackets reach a little above the capitals.
  const double v0 = base - cap_height(size) - 0.08 * size, v1 = base + descent(size);
  const double u1 = u0 + advance;
  if (!vertical) return {ax + u0, ay + v0, ax + u1, ay + v1};
  return {ax + v0, ay - u1, ax + v1, ay - u0};
}

Box TextPainter::draw(Image& image, std::string_view utf8, double x, double y, double size,
                      Rgb colour, Align align, Anchor anchor, bool vertical) {
  double advance = 0.0;
  const std::vector<Placed> placed = shape(utf8, size, &advance);
  int u0 = 0, base = 0;
  origin(advance, size, align, anchor, &u0, &base);
  const int ax = static_cast<int>(std::lround(x)), ay = static_cast<int>(std::lround(y));
  for (const Placed& p : placed) {
    const double pen = u0 + p.pen;
    const double whole = std::floor(pen);
    const int quarter = std::min(kQuarters - 1, static_cast<int>((pen - whole) * kQuarters));
    const Glyph& g = glyph(p.glyph, size, quarter);
    const int gu = static_cast<int>(whole) + g.x0, gv = base + g.y0;
    for (int j = 0; j < g.h; ++j) {
      for (int i = 0; i < g.w; ++i) {
        const unsigned char a = g.alpha[static_cast<std::size_t>(j) * g.w + i];
        if (a == 0) continue;
        const float alpha = static_cast<float>(a) / 255.0F;
        // Turned a quarter anticlockwise: along the text is up, across it is right.
        if (vertical) {
          image.blend(ax + gv + j, ay - (gu + i) - 1, colour, alpha);
        } else {
          image.blend(ax + gu + i, ay + gv + j, colour, alpha);
        }
      }
    }
  }
  return bounds(utf8, x, y, size, align, anchor, vertical);
}

}  // namespace fluidbed::chart::detail
