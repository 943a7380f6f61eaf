// The renderer's text: the block beside the beds (time, gas, particle count), colour bars with
// ticks, the arrow legends.
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "render/renderer_impl.hpp"

namespace fluidbed::render {

void Renderer::Impl::colour_bar(const Rect& bar, ColourMap map, const ColourScale& scale,
                                const FrameLayout& l, const Theme& th) {
  const int segments = scale.bands > 0 ? scale.bands : 128;
  for (int k = 0; k < segments; ++k) {
    const float y_hi =
        bar.y1 - bar.height() * static_cast<float>(k + 1) / static_cast<float>(segments);
    const float y_lo = bar.y1 - bar.height() * static_cast<float>(k) / static_cast<float>(segments);
    const double t0 = static_cast<double>(k) / segments, t1 = static_cast<double>(k + 1) / segments;
    if (scale.bands > 0) {
      rect(over, {bar.x0, y_hi, bar.x1, y_lo}, opaque(colour_at(map, 0.5 * (t0 + t1))));
    } else {
      quad(over, bar.x0, y_hi, bar.x1, y_lo, opaque(colour_at(map, t1)),
           opaque(colour_at(map, t0)));
    }
  }
  frame(over, {bar.x0 - 1, bar.y0 - 1, bar.x1 + 1, bar.y1 + 1}, 1.0f, th.faint);
  // About five ticks, as the charts choose and label them (render/ticks.hpp), decades on a
  // logarithmic scale; a shared power of ten of the labels ("×10⁻⁶") follows the title.
  const Ticks ticks =
      scale.log ? log_ticks(scale.min, scale.max, 5) : linear_ticks(scale.min, scale.max, 5);
  label(ticks.multiplier.empty() ? scale.title : scale.title + "  " + ticks.multiplier, bar.x0,
        bar.y0 - 0.6f * l.font, l.font, th.text);
  const float tick_len = 0.35f * l.font;
  const float lift = 0.5f * atlas(l.small).font->ascent();
  for (std::size_t k = 0; k < ticks.major.size(); ++k) {
    const double v = ticks.major[k];
    const float y = bar.y1 - f(scale_position(scale, v)) * bar.height();
    rect(over, {bar.x1 + 1, y - 0.5f, bar.x1 + 1 + tick_len, y + 0.5f}, th.text);
    label(ticks.labels[k], bar.x1 + 1.6f * tick_len, y + lift, l.small, th.text);
  }
}

// The text block, colour bar(s) and arrow legends right of the bed(s).
void Renderer::Impl::draw_info(const Snapshot& s, const FrameLayout& l, const RenderSettings& rs,
                               const ColourScale& scale, const Theme& th, bool with_time) {
  float y = l.info.y0 + atlas(l.big).font->ascent();
  const float x = l.info.x0;
  if (with_time) {
    label(format(("t = %." + std::to_string(rs.time_decimals) + "f s").c_str(), s.time), x, y,
          l.big, th.text);
  }
  y += 1.5f * l.font;
  if (s.has_gas()) {
    std::string u = format("U = %.2f m/s", s.superficial_velocity);
    if (s.inlet_kind == InletKind::Jet) u += format(" (jet %.1f m/s)", s.jet_velocity);
    label(u, x, y, l.font, th.text);
    y += 1.3f * l.font;
    if (with_time) label(format("\xce\x94p = %.0f Pa", s.dp), x, y, l.font, th.text);
  } else {
    label("no gas", x, y, l.font, th.text);
  }
  y += 1.3f * l.font;
  label(std::to_string(s.particles()) + " particles", x, y, l.font, th.faint);

  float below = l.colour_bar.y1;
  if (rs.colour_by != ColourBy::fixed) {
    colour_bar(l.colour_bar, ColourMap::viridis, scale, l, th);
  } else {
    label("particles: one colour", x, l.colour_bar.y0, l.font, th.text);
    below = l.colour_bar.y0;
  }
  below += 1.6f * l.font;
  const BedView& bed = l.beds.front();
  const float shaft = std::max(0.5f, 0.55f * l.wall / 2.0f + 0.1f);
  const float lift = 0.5f * atlas(l.small).font->ascent();
  if (s.has_gas() && rs.gas_arrows) {
    if (rs.gas_arrows_coloured) {
      below += 1.4f * l.font;
      const Rect bar{x, below, x + l.font, below + 0.6f * l.colour_bar.height()};
      const ColourScale gas{0.0, rs.gas_colour_max, 0, false, "gas speed (m/s)"};
      colour_bar(bar, ColourMap::inferno, gas, l, th);
      below = bar.y1 + 1.6f * l.font;
    }
    const auto len = f(s.gas_dy() * bed.scale);
    add_arrow(arrow_list, x, below, len, 0.0f, shaft,
              rs.gas_arrows_coloured
                  ? colour_at(ColourMap::inferno, rs.gas_arrow_reference / rs.gas_colour_max)
                  : th.gas_arrow);
    label(format("gas %g m/s", rs.gas_arrow_reference), x + len + 0.5f * l.font, below + lift,
          l.small, th.text);
    below += 1.3f * l.font;
  }
  if (rs.particle_arrows && s.particles() > 0) {
    const auto len = f(6.0 * s.radius[0] * bed.scale);
    add_arrow(arrow_list, x, below, len, 0.0f, shaft, th.particle_arrow);
    label(format("particle %g m/s", rs.particle_arrow_reference), x + len + 0.5f * l.font,
          below + lift, l.small, th.text);
  }
}

namespace {

// `text` in lines no wider than `width` px at the atlas's size (words kept whole; a word wider
// than the line stands alone).
std::vector<std::string> wrap(const std::string& text, float width,
                              const std::function<float(const std::string&)>& measure) {
  std::vector<std::string> lines;
  std::string line, word;
  std::istringstream words(text);
  while (words >> word) {
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && measure(longer) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace

void Renderer::Impl::draw_caption(const std::string& words, const FrameLayout& l) {
  if (words.empty()) return;
  const Rect& band = l.caption;
  const float width = band.width() - 2.0f * l.margin;
  // The largest of three sizes at which the caption fits in two lines.
  std::vector<std::string> lines;
  float size = l.big;
  for (float s : {l.big, l.font, l.small}) {
    size = s;
    lines = wrap(words, width, [&](const std::string& t) { return text_width(t, s); });
    if (lines.size() <= 2) break;
  }
  if (lines.size() > 2) {  // still too long: the second line ends in an ellipsis
    std::string rest = lines[1];
    const auto drop_last_character = [&rest] {  // a whole UTF-8 sequence
      while (!rest.empty() && (static_cast<unsigned char>(rest.back()) & 0xC0u) == 0x80u)
        rest.pop_back();
      if (!rest.empty()) rest.pop_back();
    };
    while (!rest.empty() && text_width(rest + "\xe2\x80\xa6", size) > width) drop_last_character();
    lines.resize(2);
    lines[1] = rest + "\xe2\x80\xa6";
  }
  rect(over, band, {0.11f, 0.15f, 0.26f, 1.0f});
  const float line_h = 1.25f * size;
  const float ascent = atlas(size).font->ascent();
  float y = band.y0 + 0.5f * (band.height() - line_h * static_cast<float>(lines.size())) + ascent;
  for (const std::string& line : lines) {
    label(line, 0.5f * (band.x0 + band.x1), y, size, {1.0f, 1.0f, 1.0f, 1.0f}, Align::centre);
    y += line_h;
  }
}

void Renderer::Impl::draw_bed_label(const std::string& words, const BedView& bed,
                                    const FrameLayout& l, const Theme& th) {
  const float size = l.big;
  const float w = text_width(words, size), pad = 0.35f * size;
  const float half = 0.5f * w + pad;
  const float cx =
      std::clamp(0.5f * (bed.clip.x0 + bed.clip.x1), l.margin + half,
                 std::max(l.margin + half, static_cast<float>(l.width) - l.margin - half));
  const float y0 = bed.clip.y0 + l.wall + 0.4f * size;
  const Rect box{cx - half, y0, cx + half, y0 + 1.45f * size};
  rect(over, box, {th.bed.r, th.bed.g, th.bed.b, 0.85f});
  frame(over, box, 1.0f, th.faint);
  label(words, cx, y0 + 0.35f * size + atlas(size).font->ascent() * 0.85f, size, th.text,
        Align::centre);
}

}  // namespace fluidbed::render
