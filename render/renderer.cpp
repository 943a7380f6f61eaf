#include "render/renderer.hpp"

#include "render/renderer_impl.hpp"

namespace fluidbed::render {

void Renderer::Impl::draw_bed(const Snapshot& s, const BedView& bed, const FrameLayout& l,
                              const RenderSettings& rs, const ColourScale& scale, const Theme& th,
                              bool cut_top) {
  rect(under, bed.inside, th.bed);
  const bool gas = s.has_gas() && s.gas_ux.size() == static_cast<std::size_t>(s.nx * s.ny);
  // The gas cells from the grid's bottom; a plenum's (below the floor, y < 0) are not drawn.
  const double dx = gas ? s.width / s.nx : 0.0, dy = gas ? s.gas_dy() : 0.0;
  const auto row_y = [&](int j) { return s.gas_bottom + j * dy; };  // m, the row's lower edge
  if (gas && rs.porosity_background && s.porosity.size() == s.gas_ux.size()) {
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        if (row_y(j + 1) <= 0.0) continue;
        const double eps = s.porosity[static_cast<std::size_t>(j * s.nx + i)];
        const auto t = f(std::clamp((eps - 0.35) / 0.65, 0.0, 1.0));
        const Rgb& a = th.porous_dense;
        const Rgb& b = th.porous_void;
        const Rgba c{a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t, 1};
        rect(under,
             {bed.px(i * dx), bed.py(row_y(j + 1)), bed.px((i + 1) * dx),
              bed.py(std::max(row_y(j), 0.0))},
             c);
      }
  }

  // Particles. A thick bed is seen through the front wall (z = 0): its spheres go back to front,
  // so that the nearer one covers the farther where they overlap on the picture, and each is
  // darkened for its depth (depth_shade). A monolayer keeps its order and colours.
  const bool depth = !s.z.empty() && s.z.size() == s.particles();
  const auto add_disc = [&](std::size_t i) {
    Rgb c = rs.colour_by == ColourBy::fixed
                ? rs.fixed_colour
                : colour_at(ColourMap::viridis,
                            scale_position(scale, particle_value(rs.colour_by, s, i)));
    if (depth) {
      const float shade = f(depth_shade(s, i));
      c = {c.r * shade, c.g * shade, c.b * shade};
    }
    discs.push_back({bed.px(s.x[i]), bed.py(s.y[i]), std::max(0.7f, f(s.radius[i] * bed.scale)),
                     c.r, c.g, c.b});
  };
  if (depth) {
    back_to_front.resize(s.particles());
    std::iota(back_to_front.begin(), back_to_front.end(), std::size_t{0});
    std::stable_sort(back_to_front.begin(), back_to_front.end(),
                     [&s](std::size_t a, std::size_t b) { return s.z[a] > s.z[b]; });
    for (std::size_t i : back_to_front) add_disc(i);
  } else {
    for (std::size_t i = 0; i < s.particles(); ++i) add_disc(i);
  }

  // Bubble and jet-cavity outlines (the fine cells' edges the snapshot carries), over the
  // particles.
  if (rs.bubble_outlines) {
    const float t = std::max(1.0f, 0.3f * l.wall);
    const auto& e = s.bubble_edges;
    for (std::size_t k = 0; k + 3 < e.size(); k += 4) {
      const float x0 = bed.px(e[k]), y0 = bed.py(e[k + 1]), x1 = bed.px(e[k + 2]),
                  y1 = bed.py(e[k + 3]);
      rect(over,
           {std::min(x0, x1) - 0.5f * t, std::min(y0, y1) - 0.5f * t, std::max(x0, x1) + 0.5f * t,
            std::max(y0, y1) + 0.5f * t},
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
        const double centre_y = row_y(j) + 0.5 * dy;
        if (centre_y < 0.0) continue;
        const double ux = s.gas_ux[c], uy = s.gas_uy[c];
        const double speed = std::hypot(ux, uy);
        if (!(speed > 0.0)) continue;
        const double len = std::min(speed * per, cap);
        const auto vx = f(ux / speed * len), vy = f(-uy / speed * len);
        const Rgb col =
            rs.gas_arrows_coloured
                ? colour_at(ColourMap::inferno, speed / std::max(rs.gas_colour_max, 1e-12))
                : th.gas_arrow;
        add_arrow(arrow_list, bed.px((i + 0.5) * dx) - vx / 2, bed.py(centre_y) - vy / 2, vx, vy,
                  shaft, col);
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
void Renderer::Impl::draw_close_up(const Snapshot& s, const BedView& whole, const BedView& zoom,
                                   const FrameLayout& l, const RenderSettings& rs,
                                   const ColourScale& scale, const Theme& th) {
  draw_bed(s, zoom, l, rs, scale, th, true);
  const Rect& in = zoom.inside;
  const Rect& panel = zoom.clip;
  if (zoom.zoomed) {
    draw_batches(&panel);  // what lies outside the panel is cut off
  } else {
    rect(over, {in.x0 - l.wall - 2, 0, in.x1 + l.wall + 2, in.y0}, th.page);
  }
  const float dash = std::max(3.0f, 0.5f * l.font);
  for (float x = panel.x0; x < panel.x1; x += 2.0f * dash)
    rect(over, {x, panel.y0 - 1, std::min(x + dash, panel.x1), panel.y0 + 1}, th.faint);
  if (!whole.zoomed) {  // a bracket beside the whole bed: the part the close-up shows
    const float bx = whole.inside.x1 + l.wall + 0.35f * l.font;
    const float y0 = whole.py(0.0), y1 = whole.py(l.close_up_height);
    rect(over, {bx, y1, bx + 1.5f, y0}, th.faint);
    rect(over, {bx - 0.3f * l.font, y1, bx + 1.5f, y1 + 1.5f}, th.faint);
    rect(over, {bx - 0.3f * l.font, y0 - 1.5f, bx + 1.5f, y0}, th.faint);
  }
  const std::string what =
      zoom.zoomed ? std::string("zoomed") : format("0 to %.2f m", l.close_up_height);
  // Zoomed, the factor the zoom set first (what `zoom 3` and the wheel asked for), then the
  // magnification against the whole bed.
  const std::string factor =
      zoom.zoomed && rs.zoom.factor > 1.0
          ? format(" (\xc3\x97%.1f, ", rs.zoom.factor) +
                format("\xc3\x97%.1f the whole bed)", zoom.scale / whole.scale)
          : format(" (\xc3\x97%.1f)", zoom.scale / whole.scale);
  label(what + factor, 0.5f * (panel.x0 + panel.x1),
        panel.y0 - 0.6f * l.font, l.small, th.faint, Align::centre);
}

void Renderer::Impl::draw_walls(const Snapshot& s, const BedView& bed, const FrameLayout& l,
                                const Theme& th, bool cut_top) {
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
      add_arrow(arrow_list, 0.5f * (a + b), bottom1 + len, 0.0f, -len, std::max(0.6f, 0.45f * half),
                {th.jet.r, th.jet.g, th.jet.b});
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

Renderer::Renderer(GlContext& context, const std::string& font_path)
    : impl_(std::make_unique<Impl>(context, font_path)) {}

Renderer::~Renderer() = default;

void Renderer::draw_frame(const Snapshot& s, const RenderSettings& rs, int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("render: frame size must be positive");
  const Theme th = theme(rs.dark_background);
  const FrameLayout l = frame_layout_for(s, rs, width, height);
  const ColourScale scale =
      colour_scale(rs.colour_by, s, rs.range_min, rs.range_max, rs.height_bands);
  impl_->begin(width, height, rs.samples, th);
  const BedView& whole = l.beds.front();
  impl_->draw_bed(s, whole, l, rs, scale, th);
  impl_->draw_batches(whole.zoomed ? &whole.clip : nullptr);
  if (l.beds.size() > 1) impl_->draw_close_up(s, whole, l.beds[1], l, rs, scale, th);
  // The label over the bed: on the close-up when there is one (the wider panel).
  if (!rs.bed_label.empty()) impl_->draw_bed_label(rs.bed_label, l.beds.back(), l, th);
  impl_->draw_info(s, l, rs, scale, th, true);
  if (l.caption.height() > 0.0f) impl_->draw_caption(rs.caption, l);
  impl_->flush();
}

FrameLayout frame_layout_for(const Snapshot& s, const RenderSettings& rs, int width, int height) {
  FrameLayout l = frame_layout(s, width, height, rs.close_up, rs.caption_band);
  zoom_bed(l, rs.zoom);
  return l;
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
    impl_->label(
        format(("t = %." + std::to_string(rs.time_decimals) + "f s").c_str(), snapshots[k]->time),
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
  gl.BlitFramebuffer(i(src.x0), i(fh - src.y1), i(src.x1), i(fh - src.y0), i(dst.x0),
                     i(wh - dst.y1), i(dst.x1), i(wh - dst.y0), GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

Image Renderer::read_image() {
  return impl_->read();
}

}  // namespace fluidbed::render
