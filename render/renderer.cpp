#include "render/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "core/errors.hpp"
#include "render/font.hpp"
#include "render/font_file.hpp"
#include "render/gl_objects.hpp"
#include "render/ticks.hpp"

namespace fluidbed::render {
namespace {

float f(double v) { return static_cast<float>(v); }

struct Rgba {
  float r = 0, g = 0, b = 0, a = 1;
};
Rgba opaque(Rgb c) { return {c.r, c.g, c.b, 1.0f}; }

// Vertex and instance layouts shared with the shaders (see shaders/*.vert).
struct FlatVertex {
  float x, y, r, g, b, a;
};
struct TextVertex {
  float x, y, u, v, r, g, b, a;
};
struct Disc {
  float x, y, radius, r, g, b;
};
struct Arrow {
  float x, y, vx, vy, shaft, head, head_half, r, g, b;
};

struct Theme {
  Rgba page, bed, wall, text, faint, jet;
  Rgb gas_arrow, particle_arrow;
  Rgb porous_dense, porous_void;  // porosity 0.35 and 1
  Rgba bubble{0.90f, 0.16f, 0.10f, 1};  // bubble outlines
};

Theme theme(bool dark) {
  if (dark)
    return {{0.08f, 0.08f, 0.09f, 1},
            {0.0f, 0.0f, 0.0f, 1},
            {0.75f, 0.75f, 0.78f, 1},
            {0.92f, 0.92f, 0.92f, 1},
            {0.55f, 0.55f, 0.58f, 1},
            {0.35f, 0.65f, 1.0f, 1},
            {0.55f, 0.85f, 1.0f},
            {1.0f, 1.0f, 1.0f},
            {0.30f, 0.33f, 0.40f},
            {0.02f, 0.03f, 0.08f}};
  return {{0.93f, 0.93f, 0.94f, 1},
          {1.0f, 1.0f, 1.0f, 1},
          {0.22f, 0.22f, 0.25f, 1},
          {0.08f, 0.08f, 0.10f, 1},
          {0.45f, 0.45f, 0.48f, 1},
          {0.10f, 0.35f, 0.85f, 1},
          {0.05f, 0.10f, 0.35f},
          {0.0f, 0.0f, 0.0f},
          {0.50f, 0.58f, 0.70f},
          {0.92f, 0.96f, 1.0f}};
}

void quad(std::vector<FlatVertex>& out, float x0, float y0, float x1, float y1, Rgba top,
          Rgba bottom) {
  const FlatVertex a{x0, y0, top.r, top.g, top.b, top.a};
  const FlatVertex b{x1, y0, top.r, top.g, top.b, top.a};
  const FlatVertex c{x1, y1, bottom.r, bottom.g, bottom.b, bottom.a};
  const FlatVertex d{x0, y1, bottom.r, bottom.g, bottom.b, bottom.a};
  out.insert(out.end(), {a, b, c, a, c, d});
}
void rect(std::vector<FlatVertex>& out, const Rect& r, Rgba c) {
  quad(out, r.x0, r.y0, r.x1, r.y1, c, c);
}
// A rectangle's outline `t` px wide, drawn inside it.
void frame(std::vector<FlatVertex>& out, const Rect& r, float t, Rgba c) {
  rect(out, {r.x0, r.y0, r.x1, r.y0 + t}, c);
  rect(out, {r.x0, r.y1 - t, r.x1, r.y1}, c);
  rect(out, {r.x0, r.y0 + t, r.x0 + t, r.y1 - t}, c);
  rect(out, {r.x1 - t, r.y0 + t, r.x1, r.y1 - t}, c);
}

// An arrow from (x, y) along (vx, vy) (px); the head's size follows the length, within limits.
void add_arrow(std::vector<Arrow>& out, float x, float y, float vx, float vy, float shaft_half,
               Rgb c) {
  const float len = std::hypot(vx, vy);
  if (len < 0.75f) return;
  const float head = std::min(0.45f * len, 2.5f + 0.25f * len);
  const float head_half = std::max(0.5f * head, 1.8f * shaft_half);
  out.push_back({x, y, vx, vy, shaft_half, head, head_half, c.r, c.g, c.b});
}

// The font file of the frames' text; a missing or broken file is bad input (exit status 2).
FontFile read_font(const std::string& path) {
  try {
    return load_font({path});
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

std::string format(const char* fmt, double a) {
  char buf[96];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

// A unit quad's corners (triangle strip) and the unit arrow mesh (see shaders/arrows.vert).
constexpr float kCorners[] = {-1, -1, 1, -1, -1, 1, 1, 1};
constexpr float kArrowMesh[] = {
    0, 0, -1, 0, 1, -1, -1, 0, 1, -1, 1, 0,   // shaft, first triangle
    0, 0, -1, 0, 1, -1, 1,  0, 0, 0,  1, 0,   // shaft, second triangle
    1, -1, 0, -1, 1, 0, 0,  0, 1, -1, 0, 1};  // head

enum class Align { left, centre, right };

}  // namespace

struct Renderer::Impl {
  GlContext& context;
  const GladGLContext& gl;
  FontFile font_file;
  Program particles, arrows, flat, text;
  GlName corner_vbo, disc_vbo, particle_vao;
  GlName mesh_vbo, arrow_vbo, arrow_vao;
  GlName flat_vbo, flat_vao;
  GlName text_vbo, text_vao;
  // The picture: drawn multisampled into msaa_*, resolved into resolve_*.
  GlName msaa_fbo, msaa_rb, resolve_fbo, resolve_rb;
  int fb_width = 0, fb_height = 0, fb_samples = -1;
  int max_samples = 1;

  struct Atlas {
    std::unique_ptr<FontAtlas> font;
    std::unique_ptr<GlName> texture;
  };
  std::map<int, Atlas> atlases;  // by pixel height

  // What one picture draws, in order: backgrounds, particles, arrows, overlays, text.
  std::vector<FlatVertex> under, over;
  std::vector<Disc> discs;
  std::vector<Arrow> arrow_list;
  std::map<int, std::vector<TextVertex>> text_by_size;

  Impl(GlContext& ctx, const std::string& font_path)
      : context(ctx),
        gl(ctx.gl()),
        font_file(read_font(font_path)),
        particles(gl, "particles.vert", "particles.frag"),
        arrows(gl, "arrows.vert", "flat.frag"),
        flat(gl, "flat.vert", "flat.frag"),
        text(gl, "text.vert", "text.frag"),
        corner_vbo(gl, GlName::Kind::buffer),
        disc_vbo(gl, GlName::Kind::buffer),
        particle_vao(gl, GlName::Kind::vertex_array),
        mesh_vbo(gl, GlName::Kind::buffer),
        arrow_vbo(gl, GlName::Kind::buffer),
        arrow_vao(gl, GlName::Kind::vertex_array),
        flat_vbo(gl, GlName::Kind::buffer),
        flat_vao(gl, GlName::Kind::vertex_array),
        text_vbo(gl, GlName::Kind::buffer),
        text_vao(gl, GlName::Kind::vertex_array),
        msaa_fbo(gl, GlName::Kind::framebuffer),
        msaa_rb(gl, GlName::Kind::renderbuffer),
        resolve_fbo(gl, GlName::Kind::framebuffer),
        resolve_rb(gl, GlName::Kind::renderbuffer) {
    gl.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
    setup_vertex_arrays();
  }

  // Attribute `index` of `components` floats at `offset` floats into records of `stride` floats.
  void attribute(GLuint index, int components, int stride, int offset, bool per_instance) {
    gl.EnableVertexAttribArray(index);
    gl.VertexAttribPointer(index, components, GL_FLOAT, GL_FALSE,
                           static_cast<GLsizei>(stride * sizeof(float)),
                           reinterpret_cast<const void*>(static_cast<std::size_t>(offset) * sizeof(float)));
    gl.VertexAttribDivisor(index, per_instance ? 1 : 0);
  }

  void setup_vertex_arrays() {
    gl.BindVertexArray(particle_vao.id());
    gl.BindBuffer(GL_ARRAY_BUFFER, corner_vbo.id());
    gl.BufferData(GL_ARRAY_BUFFER, sizeof kCorners, kCorners, GL_STATIC_DRAW);
    attribute(0, 2, 2, 0, false);
    gl.BindBuffer(GL_ARRAY_BUFFER, disc_vbo.id());
    attribute(1, 3, 6, 0, true);
    attribute(2, 3, 6, 3, true);

    gl.BindVertexArray(arrow_vao.id());
    gl.BindBuffer(GL_ARRAY_BUFFER, mesh_vbo.id());
    gl.BufferData(GL_ARRAY_BUFFER, sizeof kArrowMesh, kArrowMesh, GL_STATIC_DRAW);
    attribute(0, 4, 4, 0, false);
    gl.BindBuffer(GL_ARRAY_BUFFER, arrow_vbo.id());
    attribute(1, 4, 10, 0, true);
    attribute(2, 3, 10, 4, true);
    attribute(3, 3, 10, 7, true);

    gl.BindVertexArray(flat_vao.id());
    gl.BindBuffer(GL_ARRAY_BUFFER, flat_vbo.id());
    attribute(0, 2, 6, 0, false);
    attribute(1, 4, 6, 2, false);

    gl.BindVertexArray(text_vao.id());
    gl.BindBuffer(GL_ARRAY_BUFFER, text_vbo.id());
    attribute(0, 2, 8, 0, false);
    attribute(1, 2, 8, 2, false);
    attribute(2, 4, 8, 4, false);
    gl.BindVertexArray(0);
  }

  Atlas& atlas(float size) {
    const int px = std::max(6, static_cast<int>(std::lround(size)));
    auto it = atlases.find(px);
    if (it != atlases.end()) return it->second;
    Atlas a;
    a.font = std::make_unique<FontAtlas>(font_file, static_cast<float>(px));
    a.texture = std::make_unique<GlName>(gl, GlName::Kind::texture);
    gl.BindTexture(GL_TEXTURE_2D, a.texture->id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, a.font->atlas_size(), a.font->atlas_size(), 0, GL_RED,
                  GL_UNSIGNED_BYTE, a.font->atlas().data());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return atlases.emplace(px, std::move(a)).first->second;
  }

  float text_width(const std::string& s, float size) { return atlas(size).font->advance(s); }

  // Text with its baseline at y; x is its left end, centre or right end.
  void label(const std::string& s, float x, float y, float size, Rgba c, Align align = Align::left) {
    Atlas& a = atlas(size);
    if (align != Align::left) x -= a.font->advance(s) * (align == Align::centre ? 0.5f : 1.0f);
    std::vector<GlyphQuad> quads;
    a.font->layout(s, std::round(x), std::round(y), quads);
    auto& out = text_by_size[static_cast<int>(std::lround(a.font->pixel_height()))];
    for (const auto& q : quads) {
      const TextVertex v0{q.x0, q.y0, q.u0, q.v0, c.r, c.g, c.b, c.a};
      const TextVertex v1{q.x1, q.y0, q.u1, q.v0, c.r, c.g, c.b, c.a};
      const TextVertex v2{q.x1, q.y1, q.u1, q.v1, c.r, c.g, c.b, c.a};
      const TextVertex v3{q.x0, q.y1, q.u0, q.v1, c.r, c.g, c.b, c.a};
      out.insert(out.end(), {v0, v1, v2, v0, v2, v3});
    }
  }

  void clear_batches() {
    under.clear();
    over.clear();
    discs.clear();
    arrow_list.clear();
    text_by_size.clear();
  }

  // --- scene ---------------------------------------------------------------------------------

  void draw_bed(const Snapshot& s, const BedView& bed, const FrameLayout& l,
                const RenderSettings& rs, const ColourScale& scale, const Theme& th,
                bool cut_top = false) {
    rect(under, bed.inside, th.bed);
    const bool gas = s.has_gas() && s.gas_ux.size() == static_cast<std::size_t>(s.nx * s.ny);
    const double dx = gas ? s.width / s.nx : 0.0, dy = gas ? s.height / s.ny : 0.0;
    if (gas && rs.porosity_background && s.porosity.size() == s.gas_ux.size()) {
      for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i) {
          const double eps = s.porosity[static_cast<std::size_t>(j * s.nx + i)];
          const auto t = f(std::clamp((eps - 0.35) / 0.65, 0.0, 1.0));
          const Rgb& a = th.porous_dense;
          const Rgb& b = th.porous_void;
          const Rgba c{a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t, 1};
          rect(under, {bed.px(i * dx), bed.py((j + 1) * dy), bed.px((i + 1) * dx), bed.py(j * dy)},
               c);
        }
    }

    // Particles.
    for (std::size_t i = 0; i < s.particles(); ++i) {
      const Rgb c = rs.colour_by == ColourBy::fixed
                        ? rs.fixed_colour
                        : colour_at(ColourMap::viridis,
                                    scale_position(scale, particle_value(rs.colour_by, s, i)));
      discs.push_back({bed.px(s.x[i]), bed.py(s.y[i]),
                       std::max(0.7f, f(s.radius[i] * bed.scale)), c.r, c.g, c.b});
    }

    // Bubble and jet-cavity outlines (the fine cells' edges the snapshot carries), over the
    // particles.
    if (rs.bubble_outlines) {
      const float t = std::max(1.0f, 0.3f * l.wall);
      const auto& e = s.bubble_edges;
      for (std::size_t k = 0; k + 3 < e.size(); k += 4) {
        const float x0 = bed.px(e[k]), y0 = bed.py(e[k + 1]), x1 = bed.px(e[k + 2]),
                    y1 = bed.py(e[k + 3]);
        rect(over, {std::min(x0, x1) - 0.5f * t, std::min(y0, y1) - 0.5f * t,
                    std::max(x0, x1) + 0.5f * t, std::max(y0, y1) + 0.5f * t},
             th.bubble);
      }
    }

    const float shaft = std::max(0.5f, 0.55f * l.wall / 2.0f + 0.1f);
    // Gas velocity at cell centres, centred on them: the reference speed spans one cell height;
    // faster gas (the jet) is capped at 1.5 cell heights so arrows stay near their cells.
    if (gas && rs.gas_arrows) {
      const double per = dy * bed.scale / std::max(rs.gas_arrow_reference, 1e-12);  // px per m/s
      const double cap = 1.5 * dy * bed.scale;
      for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i) {
          const auto c = static_cast<std::size_t>(j * s.nx + i);
          const double ux = s.gas_ux[c], uy = s.gas_uy[c];
          const double speed = std::hypot(ux, uy);
          if (!(speed > 0.0)) continue;
          const double len = std::min(speed * per, cap);
          const auto vx = f(ux / speed * len), vy = f(-uy / speed * len);
          const Rgb col = rs.gas_arrows_coloured
                              ? colour_at(ColourMap::inferno, speed / std::max(rs.gas_colour_max, 1e-12))
                              : th.gas_arrow;
          add_arrow(arrow_list, bed.px((i + 0.5) * dx) - vx / 2, bed.py((j + 0.5) * dy) - vy / 2,
                    vx, vy, shaft, col);
        }
    }
    // Particle velocity from each centre: the reference speed spans three diameters; capped at
    // twice that.
    if (rs.particle_arrows) {
      for (std::size_t i = 0; i < s.particles(); ++i) {
        const double speed = std::hypot(s.vx[i], s.vy[i]);
        if (!(speed > 0.0)) continue;
        const double unit = 6.0 * s.radius[i] * bed.scale;
        const double len = std::min(speed / std::max(rs.particle_arrow_reference, 1e-12), 2.0) * unit;
        add_arrow(arrow_list, bed.px(s.x[i]), bed.py(s.y[i]), f(s.vx[i] / speed * len),
                  f(-s.vy[i] / speed * len), shaft, th.particle_arrow);
      }
    }
    draw_walls(s, bed, l, th, cut_top);
  }

  // The bed's lower part, magnified (layout: the frame's second panel): drawn like the bed, then
  // whatever reaches above its window is covered, and the cut is marked with a dashed line. A
  // bracket beside the whole bed shows which part this is.
  void draw_close_up(const Snapshot& s, const BedView& whole, const BedView& zoom,
                     const FrameLayout& l, const RenderSettings& rs, const ColourScale& scale,
                     const Theme& th) {
    draw_bed(s, zoom, l, rs, scale, th, true);
    const Rect& in = zoom.inside;
    rect(over, {in.x0 - l.wall - 2, 0, in.x1 + l.wall + 2, in.y0}, th.page);
    const float dash = std::max(3.0f, 0.5f * l.font);
    for (float x = in.x0 - l.wall; x < in.x1 + l.wall; x += 2.0f * dash)
      rect(over, {x, in.y0 - 1, std::min(x + dash, in.x1 + l.wall), in.y0 + 1}, th.faint);
    const float bx = whole.inside.x1 + l.wall + 0.35f * l.font;
    const float y0 = whole.py(0.0), y1 = whole.py(l.close_up_height);
    rect(over, {bx, y1, bx + 1.5f, y0}, th.faint);
    rect(over, {bx - 0.3f * l.font, y1, bx + 1.5f, y1 + 1.5f}, th.faint);
    rect(over, {bx - 0.3f * l.font, y0 - 1.5f, bx + 1.5f, y0}, th.faint);
    label(format("0 to %.2f m", l.close_up_height) + format(" (\xc3\x97%.1f)", zoom.scale / whole.scale),
          0.5f * (in.x0 + in.x1), in.y0 - 0.6f * l.font, l.small, th.faint, Align::centre);
  }

  void draw_walls(const Snapshot& s, const BedView& bed, const FrameLayout& l, const Theme& th,
                  bool cut_top) {
    const Rect& in = bed.inside;
    const float t = l.wall;
    const bool top = s.top_wall && !cut_top;
    rect(over, {in.x0 - t, in.y0 - (top ? t : 0.0f), in.x0, in.y1 + t}, th.wall);
    rect(over, {in.x1, in.y0 - (top ? t : 0.0f), in.x1 + t, in.y1 + t}, th.wall);
    if (top) rect(over, {in.x0, in.y0 - t, in.x1, in.y0}, th.wall);
    const float bottom0 = in.y1, bottom1 = in.y1 + t;
    if (s.inlet_kind == InletKind::Jet && s.jet_width > 0.0) {
      // The slots: gaps in the bottom wall, each with its jet's arrow coming up into it.
      const int jets = std::max(1, s.jets);
      float wall_from = in.x0 - t;
      for (int k = 0; k < jets; ++k) {
        const double centre = (k + 0.5) * s.width / jets;
        const float a = bed.px(centre - 0.5 * s.jet_width), b = bed.px(centre + 0.5 * s.jet_width);
        rect(over, {wall_from, bottom0, a, bottom1}, th.wall);
        wall_from = b;
        const float len = 1.1f * l.font;
        const float half = std::max(1.0f, 0.5f * (b - a) - 0.5f);
        add_arrow(arrow_list, 0.5f * (a + b), bottom1 + len, 0.0f, -len,
                  std::max(0.6f, 0.45f * half), {th.jet.r, th.jet.g, th.jet.b});
      }
      rect(over, {wall_from, bottom0, in.x1 + t, bottom1}, th.wall);
    } else if (s.inlet_kind == InletKind::Uniform) {
      // A distributor: the bottom wall dashed.
      const float dash = std::max(3.0f, 0.6f * l.font);
      rect(over, {in.x0 - t, bottom0, in.x0, bottom1}, th.wall);
      rect(over, {in.x1, bottom0, in.x1 + t, bottom1}, th.wall);
      for (float x = in.x0; x < in.x1; x += 2.0f * dash)
        rect(over, {x, bottom0, std::min(x + dash, in.x1), bottom1}, th.wall);
    } else {
      rect(over, {in.x0 - t, bottom0, in.x1 + t, bottom1}, th.wall);
    }
  }

  // --- legends -------------------------------------------------------------------------------

  void colour_bar(const Rect& bar, ColourMap map, const ColourScale& scale, const FrameLayout& l,
                  const Theme& th) {
    const int segments = scale.bands > 0 ? scale.bands : 128;
    for (int k = 0; k < segments; ++k) {
      const float y_hi = bar.y1 - bar.height() * static_cast<float>(k + 1) / static_cast<float>(segments);
      const float y_lo = bar.y1 - bar.height() * static_cast<float>(k) / static_cast<float>(segments);
      const double t0 = static_cast<double>(k) / segments, t1 = static_cast<double>(k + 1) / segments;
      if (scale.bands > 0) {
        rect(over, {bar.x0, y_hi, bar.x1, y_lo}, opaque(colour_at(map, 0.5 * (t0 + t1))));
      } else {
        quad(over, bar.x0, y_hi, bar.x1, y_lo, opaque(colour_at(map, t1)), opaque(colour_at(map, t0)));
      }
    }
    frame(over, {bar.x0 - 1, bar.y0 - 1, bar.x1 + 1, bar.y1 + 1}, 1.0f, th.faint);
    // About five ticks, as the charts choose and label them (render/ticks.hpp); a shared power
    // of ten of the labels ("×10⁻⁶") follows the title.
    const Ticks ticks = linear_ticks(scale.min, scale.max, 5);
    label(ticks.multiplier.empty() ? scale.title : scale.title + "  " + ticks.multiplier, bar.x0,
          bar.y0 - 0.6f * l.font, l.font, th.text);
    const float tick_len = 0.35f * l.font;
    const float lift = 0.5f * atlas(l.small).font->ascent();
    for (std::size_t k = 0; k < ticks.major.size(); ++k) {
      const double v = ticks.major[k];
      const float y = bar.y1 - f((v - scale.min) / (scale.max - scale.min)) * bar.height();
      rect(over, {bar.x1 + 1, y - 0.5f, bar.x1 + 1 + tick_len, y + 0.5f}, th.text);
      label(ticks.labels[k], bar.x1 + 1.6f * tick_len, y + lift, l.small, th.text);
    }
  }

  // The text block, colour bar(s) and arrow legends right of the bed(s).
  void draw_info(const Snapshot& s, const FrameLayout& l, const RenderSettings& rs,
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
        colour_bar(bar, ColourMap::inferno, {0.0, rs.gas_colour_max, 0, "gas speed (m/s)"}, l, th);
        below = bar.y1 + 1.6f * l.font;
      }
      const auto len = f(s.height / s.ny * bed.scale);
      add_arrow(arrow_list, x, below, len, 0.0f, shaft,
                rs.gas_arrows_coloured ? colour_at(ColourMap::inferno, rs.gas_arrow_reference / rs.gas_colour_max)
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

  // --- GL ------------------------------------------------------------------------------------

  void begin(int width, int height, int samples, const Theme& th) {
    samples = std::clamp(samples, 1, std::max(1, max_samples));
    if (width != fb_width || height != fb_height || samples != fb_samples) {
      gl.BindRenderbuffer(GL_RENDERBUFFER, resolve_rb.id());
      gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
      gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo.id());
      gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_rb.id());
      check_framebuffer("resolve");
      if (samples > 1) {
        gl.BindRenderbuffer(GL_RENDERBUFFER, msaa_rb.id());
        gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
        gl.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo.id());
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_rb.id());
        check_framebuffer("multisample");
      }
      fb_width = width;
      fb_height = height;
      fb_samples = samples;
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, fb_samples > 1 ? msaa_fbo.id() : resolve_fbo.id());
    gl.Viewport(0, 0, width, height);
    gl.ClearColor(th.page.r, th.page.g, th.page.b, 1.0f);
    gl.Clear(GL_COLOR_BUFFER_BIT);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Enable(GL_BLEND);
    gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }

  void check_framebuffer(const char* what) {
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error(std::string("render: the ") + what + " framebuffer is incomplete");
  }

  void use(const Program& p) {
    gl.UseProgram(p.id());
    gl.Uniform2f(p.uniform("u_screen"), static_cast<float>(fb_width), static_cast<float>(fb_height));
  }

  template <class T>
  void upload(const GlName& vbo, const std::vector<T>& data) {
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo.id());
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                  GL_STREAM_DRAW);
  }

  void draw_flat(const std::vector<FlatVertex>& v) {
    if (v.empty()) return;
    use(flat);
    gl.BindVertexArray(flat_vao.id());
    upload(flat_vbo, v);
    gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(v.size()));
  }

  void flush() {
    draw_flat(under);
    if (!discs.empty()) {
      use(particles);
      gl.BindVertexArray(particle_vao.id());
      upload(disc_vbo, discs);
      gl.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(discs.size()));
    }
    if (!arrow_list.empty()) {
      use(arrows);
      gl.BindVertexArray(arrow_vao.id());
      upload(arrow_vbo, arrow_list);
      gl.DrawArraysInstanced(GL_TRIANGLES, 0, 9, static_cast<GLsizei>(arrow_list.size()));
    }
    draw_flat(over);
    if (!text_by_size.empty()) {
      use(text);
      gl.Uniform1i(text.uniform("u_atlas"), 0);
      gl.ActiveTexture(GL_TEXTURE0);
      gl.BindVertexArray(text_vao.id());
      for (const auto& [size, verts] : text_by_size) {
        gl.BindTexture(GL_TEXTURE_2D, atlases.at(size).texture->id());
        upload(text_vbo, verts);
        gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(verts.size()));
      }
    }
    gl.BindVertexArray(0);
    if (fb_samples > 1) {
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo.id());
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo.id());
      gl.BlitFramebuffer(0, 0, fb_width, fb_height, 0, 0, fb_width, fb_height, GL_COLOR_BUFFER_BIT,
                         GL_NEAREST);
    }
    clear_batches();
  }

  Image read() {
    Image img;
    img.width = fb_width;
    img.height = fb_height;
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(fb_width) * static_cast<std::size_t>(fb_height) * 4);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo.id());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    img.rgb.resize(static_cast<std::size_t>(fb_width) * static_cast<std::size_t>(fb_height) * 3);
    // GL's rows start at the bottom; an image's at the top.
    for (int y = 0; y < fb_height; ++y) {
      const std::uint8_t* src = rgba.data() + static_cast<std::size_t>(fb_height - 1 - y) * static_cast<std::size_t>(fb_width) * 4;
      std::uint8_t* dst = img.rgb.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(fb_width) * 3;
      for (int x = 0; x < fb_width; ++x, src += 4, dst += 3) {
        dst[0] = src[0];
        dst[1] = src[1];
        dst[2] = src[2];
      }
    }
    return img;
  }
};

Renderer::Renderer(GlContext& context, const std::string& font_path)
    : impl_(std::make_unique<Impl>(context, font_path)) {}

Renderer::~Renderer() = default;

void Renderer::draw_frame(const Snapshot& s, const RenderSettings& rs, int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("render: frame size must be positive");
  const Theme th = theme(rs.dark_background);
  const FrameLayout l = frame_layout(s, width, height, rs.close_up);
  const ColourScale scale = colour_scale(rs.colour_by, s, rs.range_min, rs.range_max, rs.height_bands);
  impl_->begin(width, height, rs.samples, th);
  impl_->draw_bed(s, l.beds.front(), l, rs, scale, th);
  if (l.beds.size() > 1) impl_->draw_close_up(s, l.beds.front(), l.beds[1], l, rs, scale, th);
  impl_->draw_info(s, l, rs, scale, th, true);
  impl_->flush();
}

Image Renderer::render_frame(const Snapshot& s, const RenderSettings& rs, int width, int height) {
  draw_frame(s, rs, width, height);
  return impl_->read();
}

Image Renderer::render_montage(const std::vector<const Snapshot*>& snapshots,
                               const RenderSettings& rs, int height) {
  if (snapshots.empty()) throw std::invalid_argument("render: a montage needs snapshots");
  const Snapshot& first = *snapshots.front();
  const Theme th = theme(rs.dark_background);
  const FrameLayout l = montage_layout(first, static_cast<int>(snapshots.size()), height);
  const ColourScale scale =
      colour_scale(rs.colour_by, first, rs.range_min, rs.range_max, rs.height_bands);
  impl_->begin(l.width, l.height, rs.montage_samples, th);
  for (std::size_t k = 0; k < snapshots.size(); ++k) {
    const BedView& bed = l.beds[k];
    impl_->draw_bed(*snapshots[k], bed, l, rs, scale, th);
    impl_->label(format(("t = %." + std::to_string(rs.time_decimals) + "f s").c_str(), snapshots[k]->time),
                 0.5f * (bed.inside.x0 + bed.inside.x1), l.label_y, l.font, th.text, Align::centre);
  }
  impl_->draw_info(first, l, rs, scale, th, false);
  impl_->flush();
  return impl_->read();
}

void Renderer::blit_to_default(int width, int height) {
  const auto& gl = impl_->gl;
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, impl_->resolve_fbo.id());
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl.BlitFramebuffer(0, 0, impl_->fb_width, impl_->fb_height, 0, 0, width, height,
                     GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

void Renderer::blit_region_to_default(const Rect& src, const Rect& dst, int window_height) {
  const auto& gl = impl_->gl;
  const auto fh = static_cast<float>(impl_->fb_height);
  const auto wh = static_cast<float>(window_height);
  const auto i = [](float v) { return static_cast<GLint>(std::lround(v)); };
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, impl_->resolve_fbo.id());
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  // GL's rows count from the bottom.
  gl.BlitFramebuffer(i(src.x0), i(fh - src.y1), i(src.x1), i(fh - src.y0), i(dst.x0), i(wh - dst.y1),
                     i(dst.x1), i(wh - dst.y0), GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

Image Renderer::read_image() { return impl_->read(); }

}  // namespace fluidbed::render
