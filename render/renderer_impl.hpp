#pragma once
// The renderer's insides, shared by its source files: renderer.cpp (GL, the beds) and
// renderer_legend.cpp (the text block, colour bars, caption and the label over the bed).
#include "render/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/text_format.hpp"
#include "render/font.hpp"
#include "render/font_file.hpp"
#include "render/gl_objects.hpp"
#include "render/ticks.hpp"

namespace fluidbed::render {
namespace detail {

inline float f(double v) {
  return static_cast<float>(v);
}

struct Rgba {
  float r = 0, g = 0, b = 0, a = 1;
};
inline Rgba opaque(Rgb c) {
  return {c.r, c.g, c.b, 1.0f};
}

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
  Rgb porous_dense, porous_void;        // porosity 0.35 and 1
  Rgba bubble{0.90f, 0.16f, 0.10f, 1};  // bubble outlines
};

inline Theme theme(bool dark) {
  if (dark)
    return {{0.08f, 0.08f, 0.09f, 1}, {0.0f, 0.0f, 0.0f, 1},    {0.75f, 0.75f, 0.78f, 1},
            {0.92f, 0.92f, 0.92f, 1}, {0.55f, 0.55f, 0.58f, 1}, {0.35f, 0.65f, 1.0f, 1},
            {0.55f, 0.85f, 1.0f},     {1.0f, 1.0f, 1.0f},       {0.30f, 0.33f, 0.40f},
            {0.02f, 0.03f, 0.08f}};
  return {{0.93f, 0.93f, 0.94f, 1}, {1.0f, 1.0f, 1.0f, 1},    {0.22f, 0.22f, 0.25f, 1},
          {0.08f, 0.08f, 0.10f, 1}, {0.45f, 0.45f, 0.48f, 1}, {0.10f, 0.35f, 0.85f, 1},
          {0.05f, 0.10f, 0.35f},    {0.0f, 0.0f, 0.0f},       {0.50f, 0.58f, 0.70f},
          {0.92f, 0.96f, 1.0f}};
}

inline void quad(std::vector<FlatVertex>& out, float x0, float y0, float x1, float y1, Rgba top,
                 Rgba bottom) {
  const FlatVertex a{x0, y0, top.r, top.g, top.b, top.a};
  const FlatVertex b{x1, y0, top.r, top.g, top.b, top.a};
  const FlatVertex c{x1, y1, bottom.r, bottom.g, bottom.b, bottom.a};
  const FlatVertex d{x0, y1, bottom.r, bottom.g, bottom.b, bottom.a};
  out.insert(out.end(), {a, b, c, a, c, d});
}
inline void rect(std::vector<FlatVertex>& out, const Rect& r, Rgba c) {
  quad(out, r.x0, r.y0, r.x1, r.y1, c, c);
}
// A rectangle's outline `t` px wide, drawn inside it.
inline void frame(std::vector<FlatVertex>& out, const Rect& r, float t, Rgba c) {
  rect(out, {r.x0, r.y0, r.x1, r.y0 + t}, c);
  rect(out, {r.x0, r.y1 - t, r.x1, r.y1}, c);
  rect(out, {r.x0, r.y0 + t, r.x0 + t, r.y1 - t}, c);
  rect(out, {r.x1 - t, r.y0 + t, r.x1, r.y1 - t}, c);
}

// An arrow from (x, y) along (vx, vy) (px); the head's size follows the length, within limits.
inline void add_arrow(std::vector<Arrow>& out, float x, float y, float vx, float vy,
                      float shaft_half, Rgb c) {
  const float len = std::hypot(vx, vy);
  if (len < 0.75f) return;
  const float head = std::min(0.45f * len, 2.5f + 0.25f * len);
  const float head_half = std::max(0.5f * head, 1.8f * shaft_half);
  out.push_back({x, y, vx, vy, shaft_half, head, head_half, c.r, c.g, c.b});
}

// The font file of the frames' text; a missing or broken file is bad input (exit status 2).
inline FontFile read_font(const std::string& path) {
  try {
    return load_font({path});
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

inline std::string format(const char* fmt, double a) { return format_number(fmt, a); }

// A unit quad's corners (triangle strip) and the unit arrow mesh (see shaders/arrows.vert).
inline constexpr float kCorners[] = {-1, -1, 1, -1, -1, 1, 1, 1};
inline constexpr float kArrowMesh[] = {
    0, 0,  -1, 0,  1, -1, -1, 0, 1, -1, 1, 0,   // shaft, first triangle
    0, 0,  -1, 0,  1, -1, 1,  0, 0, 0,  1, 0,   // shaft, second triangle
    1, -1, 0,  -1, 1, 0,  0,  0, 1, -1, 0, 1};  // head

enum class Align { left, centre, right };

}  // namespace detail

using namespace detail;

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
  std::vector<std::size_t> back_to_front;  // a thick bed's particle order (kept for its capacity)

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
    gl.VertexAttribPointer(
        index, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride * sizeof(float)),
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
  void label(const std::string& s, float x, float y, float size, Rgba c,
             Align align = Align::left) {
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

  // --- scene (renderer.cpp) -------------------------------------------------------------------

  void draw_bed(const Snapshot& s, const BedView& bed, const FrameLayout& l,
                const RenderSettings& rs, const ColourScale& scale, const Theme& th,
                bool cut_top = false);
  // The bed's lower part, magnified (layout: the frame's second panel): drawn like the bed, then
  // whatever reaches above its window is covered, and the cut is marked with a dashed line. A
  // bracket beside the whole bed shows which part this is.
  void draw_close_up(const Snapshot& s, const BedView& whole, const BedView& zoom,
                     const FrameLayout& l, const RenderSettings& rs, const ColourScale& scale,
                     const Theme& th);
  void draw_walls(const Snapshot& s, const BedView& bed, const FrameLayout& l, const Theme& th,
                  bool cut_top);

  // --- legends (renderer_legend.cpp) ----------------------------------------------------------

  // The caption in its band across the top (wrapped to two lines, smaller when still too long),
  // and a label over a bed (the regime in words) on a light box in the bed's upper part.
  void draw_caption(const std::string& words, const FrameLayout& l);
  void draw_bed_label(const std::string& words, const BedView& bed, const FrameLayout& l,
                      const Theme& th);

  void colour_bar(const Rect& bar, ColourMap map, const ColourScale& scale, const FrameLayout& l,
                  const Theme& th);
  // The text block, colour bar(s) and arrow legends right of the bed(s).
  void draw_info(const Snapshot& s, const FrameLayout& l, const RenderSettings& rs,
                 const ColourScale& scale, const Theme& th, bool with_time);

  // --- GL ------------------------------------------------------------------------------------

  void begin(int width, int height, int samples, const Theme& th) {
    samples = std::clamp(samples, 1, std::max(1, max_samples));
    if (width != fb_width || height != fb_height || samples != fb_samples) {
      gl.BindRenderbuffer(GL_RENDERBUFFER, resolve_rb.id());
      gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
      gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo.id());
      gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                 resolve_rb.id());
      check_framebuffer("resolve");
      if (samples > 1) {
        gl.BindRenderbuffer(GL_RENDERBUFFER, msaa_rb.id());
        gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
        gl.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo.id());
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                   msaa_rb.id());
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
    gl.Uniform2f(p.uniform("u_screen"), static_cast<float>(fb_width),
                 static_cast<float>(fb_height));
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

  // Draws what was batched so far, inside `clip` (frame px, y down) when it is given (a zoomed
  // bed), and empties the batches.
  void draw_batches(const Rect* clip = nullptr) {
    if (clip) {
      const auto i = [](float v) { return static_cast<GLint>(std::lround(v)); };
      gl.Enable(GL_SCISSOR_TEST);
      gl.Scissor(i(clip->x0), i(static_cast<float>(fb_height) - clip->y1),
                 std::max(0, i(clip->width())), std::max(0, i(clip->height())));
    }
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
    if (clip) gl.Disable(GL_SCISSOR_TEST);
    clear_batches();
  }

  // The rest of the batches, then the multisampled picture resolved.
  void flush() {
    draw_batches();
    if (fb_samples > 1) {
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo.id());
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo.id());
      gl.BlitFramebuffer(0, 0, fb_width, fb_height, 0, 0, fb_width, fb_height, GL_COLOR_BUFFER_BIT,
                         GL_NEAREST);
    }
  }

  Image read() {
    Image img;
    img.width = fb_width;
    img.height = fb_height;
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(fb_width) *
                                   static_cast<std::size_t>(fb_height) * 4);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo.id());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    img.rgb.resize(static_cast<std::size_t>(fb_width) * static_cast<std::size_t>(fb_height) * 3);
    // GL's rows start at the bottom; an image's at the top.
    for (int y = 0; y < fb_height; ++y) {
      const std::uint8_t* src = rgba.data() + static_cast<std::size_t>(fb_height - 1 - y) *
                                                  static_cast<std::size_t>(fb_width) * 4;
      std::uint8_t* dst =
          img.rgb.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(fb_width) * 3;
      for (int x = 0; x < fb_width; ++x, src += 4, dst += 3) {
        dst[0] = src[0];
        dst[1] = src[1];
        dst[2] = src[2];
      }
    }
    return img;
  }
};

}  // namespace fluidbed::render
