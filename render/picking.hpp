#pragma once
// The viewer's geometry, without GL: where the drawn frame lands in the window (zoom and pan),
// which particle is under the mouse, and what touches it. Pure arithmetic on a snapshot and the
// frame's layout, so tests can check it pixel by pixel.
#include <cstddef>
#include <optional>
#include <vector>

#include "render/layout.hpp"
#include "sim/snapshot.hpp"

namespace fluidbed::render {

// Zoom and pan of a frame shown in a window area: the visible part of the frame is a rectangle
// 1 / zoom of its size centred at (centre_x, centre_y), fractions of the frame (y down).
struct ViewTransform {
  double zoom = 1.0;                      // >= 1
  double centre_x = 0.5, centre_y = 0.5;  // fraction of the frame's width and height

  // Keeps zoom in [1, max_zoom] and the visible rectangle inside the frame.
  void clamp(double max_zoom = 16.0);
  // Zooms by `factor` keeping the frame point under window fraction (u, v) of the area in place.
  void zoom_about(double factor, double u, double v);
  // Moves the view by a drag of (du, dv) fractions of the area (the picture follows the mouse).
  void pan_by(double du, double dv);
};

// The visible rectangle of a frame of fw x fh pixels (frame pixels, y down).
Rect visible_rect(const ViewTransform& t, int fw, int fh);
// A window point -> frame pixels, for a frame of fw x fh shown in `area` (window pixels, y down).
void window_to_frame(const ViewTransform& t, const Rect& area, int fw, int fh, double wx, double wy,
                     double& fx, double& fy);
void frame_to_window(const ViewTransform& t, const Rect& area, int fw, int fh, double fx, double fy,
                     double& wx, double& wy);

// A frame point (pixels) in a bed panel -> metres; false outside the panel's bed (or, in the
// close-up, above its height).
bool frame_to_world(const FrameLayout& l, double fx, double fy, double& x, double& y);
// The bed panel's pixel for a point in metres (the main panel, beds[0]).
void world_to_frame(const FrameLayout& l, double x, double y, double& fx, double& fy);

// The particle drawn under frame point (fx, fy): the one whose disc holds the point (the nearest
// centre when discs overlap). A tiny disc is taken `min_pixels` wide at least, so it can be hit.
std::optional<std::size_t> pick_particle(const Snapshot& s, const FrameLayout& l, double fx,
                                         double fy, double min_pixels = 3.0);

// What touches particle i: other particles whose centres are closer than the sum of the radii,
// and the walls its disc crosses.
struct ParticleContacts {
  std::vector<std::size_t> particles;
  int walls = 0;             // left, right, bottom, top (when the bed has a top wall)
  double max_overlap = 0.0;  // largest pair overlap ratio 1 - L / (R_i + R_j)
  std::size_t count() const { return particles.size() + static_cast<std::size_t>(walls); }
};
ParticleContacts contacts_of(const Snapshot& s, std::size_t i);

}  // namespace fluidbed::render
