#pragma once
// The viewer's geometry, without GL: which bed panel and which particle are under the mouse
// (zoomed panels included: render/layout.hpp, zoom_bed), and what touches a particle. Pure
// arithmetic on a snapshot and the frame's layout, so tests can check it pixel by pixel.
#include <cstddef>
#include <optional>
#include <vector>

#include "render/layout.hpp"
#include "sim/snapshot.hpp"

namespace fluidbed::render {

// The bed panel under a frame point (pixels): its index in l.beds, or -1.
int bed_at(const FrameLayout& l, double fx, double fy);
// A frame point (pixels) in a bed panel -> metres; false outside the panels' beds (or, in the
// close-up, above its height).
bool frame_to_world(const FrameLayout& l, double fx, double fy, double& x, double& y);
// The bed panel's pixel for a point in metres (the main panel, beds[0]).
void world_to_frame(const FrameLayout& l, double x, double y, double& fx, double& fy);

// The particle drawn under frame point (fx, fy): the one whose disc holds the point; when discs
// overlap, the front-most in a thick bed (smallest z), else the nearest centre. A tiny disc is
// taken `min_pixels` wide at least, so it can be hit.
std::optional<std::size_t> pick_particle(const Snapshot& s, const FrameLayout& l, double fx,
                                         double fy, double min_pixels = 3.0);

// What touches particle i: other particles whose centres are closer than the sum of the radii
// (in three dimensions in a thick bed), and the walls its sphere crosses.
struct ParticleContacts {
  std::vector<std::size_t> particles;
  int walls = 0;  // left, right, bottom, top (when the bed has a top wall), front and back (a
                  // thick bed)
  double max_overlap = 0.0;  // largest pair overlap ratio 1 - L / (R_i + R_j)
  std::size_t count() const { return particles.size() + static_cast<std::size_t>(walls); }
};
ParticleContacts contacts_of(const Snapshot& s, std::size_t i);

}  // namespace fluidbed::render
