#pragma once
// What a particle's colour shows: one quantity of the snapshot through a colour map over a fixed
// range (fixed so that a video's colours mean the same in every frame), or one fixed colour.
// The modes and their names: render/colour_by.hpp.
#include <string>

#include "render/colour_by.hpp"
#include "render/colour_map.hpp"
#include "sim/snapshot.hpp"

namespace fluidbed::render {

struct ColourScale {
  double min = 0.0, max = 1.0;  // value range mapped onto the colour map (unit of the quantity)
  int bands = 0;                // > 0: quantised into this many bands (height)
  bool log = false;             // positions by log(value) (0 < min); at or below min: the bottom
  std::string title;            // "speed (m/s)"
};

// The default range for a quantity: speed 0-1.5 m/s, overlap 0-1 %, height from 0 to the highest
// initial centre, depth from the front wall (0) to the back wall (the slab's thickness).
// Force and torque span decades in a bed (in the paper's bed at 0.6 s, a resting sphere carries
// about its weight, 9e-4 N, and an impact up to 0.7 N; half the spheres touch nothing and have no
// torque), so a linear range drew 96 % of the spheres in its darkest tenth: they are on a
// logarithmic scale of four decades up to the top of the paper's Fig. 14 legends, force
// 7e-5-0.7 N and torque 3e-8-3e-4 N m.
// `min < max` in `range` overrides the default; for force and torque it stays logarithmic when
// min > 0 and is linear from min <= 0.
ColourScale colour_scale(ColourBy c, const Snapshot& s, double range_min, double range_max,
                         int height_bands);

// The particle's value of the quantity (unit of the quantity). A monolayer (no z) has every
// centre on the mid-plane, so its depth is half the thickness: one colour, the scale's middle.
double particle_value(ColourBy c, const Snapshot& s, std::size_t i);

// How bright particle i is drawn for its depth in a thick bed: 1 for a sphere touching the front
// wall (z = r), falling linearly to kBackShade touching the back wall (z = thickness - r), so the
// front layer stands out against those behind it. 1 in a monolayer (no z): the paper's pictures.
inline constexpr double kBackShade = 0.6;
double depth_shade(const Snapshot& s, std::size_t i);

// Where `value` falls on the scale, in [0, 1] (banded scales give the band's centre).
double scale_position(const ColourScale& scale, double value);
// The value at position t in [0, 1] of an unbanded scale (the inverse of scale_position).
double scale_value(const ColourScale& scale, double t);

}  // namespace fluidbed::render
