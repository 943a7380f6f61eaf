#pragma once
// Draws engine snapshots: the bed's walls and jet slot, the particles at true size coloured by a
// chosen quantity, gas and particle velocity arrows, the porosity field, a colour bar with ticks
// and units, and the time and gas velocity. Everything comes from one snapshot (or, for a
// montage, one per panel); nothing reads the live simulation.
//
// The renderer draws into its own framebuffer (multisampled, then resolved) with the context it
// was given, which must be current on the calling thread; the picture is read back as an Image or
// copied to a window's default framebuffer.
#include <memory>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/layout.hpp"
#include "render/render_settings.hpp"
#include "sim/snapshot.hpp"

namespace fluidbed::render {

// The layout draw_frame uses for these settings: frame_layout with the close-up and the caption
// band, the zoom applied (the viewer picks particles with the same one).
FrameLayout frame_layout_for(const Snapshot& s, const RenderSettings& rs, int width, int height);

class Renderer {
 public:
  // `font_path`: a TrueType font (assets/fonts/DejaVuSans.ttf); InputError if unreadable.
  Renderer(GlContext& context, const std::string& font_path);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws one frame of width x height px (layout: frame_layout) and reads it back.
  Image render_frame(const Snapshot& s, const RenderSettings& settings, int width, int height);
  // Draws one frame without reading it back (a window then calls blit_to_default).
  void draw_frame(const Snapshot& s, const RenderSettings& settings, int width, int height);
  // Several snapshots side by side, each bed `height` px tall with its time under it (layout:
  // montage_layout); the width follows from the count.
  Image render_montage(const std::vector<const Snapshot*>& snapshots,
                       const RenderSettings& settings, int height);
  // Copies the last drawn picture to the default framebuffer (a window), scaled to fit.
  void blit_to_default(int width, int height);
  // Copies the part `src` of the last drawn picture (its pixels, y down) onto `dst` of the default
  // framebuffer (window pixels, y down, a window `window_height` tall): the viewer's zoom and pan.
  void blit_region_to_default(const Rect& src, const Rect& dst, int window_height);
  // The last drawn picture.
  Image read_image();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fluidbed::render
