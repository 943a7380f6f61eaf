#pragma once
// What a frame shows and how (plain settings with defaults; units in the comments).
#include <cmath>
#include <string>

#include "render/colour_map.hpp"
#include "render/colour_modes.hpp"
#include "render/layout.hpp"

namespace fluidbed::render {

struct RenderSettings {
  ColourBy colour_by = ColourBy::speed;
  double range_min = 0.0, range_max = 0.0;  // colour range (unit of the quantity); min >= max:
                                            // the quantity's default (see colour_scale)
  int height_bands = 8;                     // bands of the `height` mode
  Rgb fixed_colour{0.23f, 0.42f, 0.70f};    // the `fixed` mode's colour
  bool gas_arrows = true;                   // gas velocity at cell centres (Fig. 14b)
  bool gas_arrows_coloured = false;         // coloured by speed (inferno) instead of one colour
  double gas_arrow_reference = 10.0;        // m/s drawn one cell height long
  double gas_colour_max = 20.0;             // m/s at the top of the gas colour bar
  bool particle_arrows = false;             // particle velocity at centres (Fig. 14a)
  double particle_arrow_reference = 1.0;    // m/s drawn three particle diameters long
  bool porosity_background = false;         // the gas cells' porosity behind the particles
  bool bubble_outlines = false;             // the outlines the snapshot carries (bubble_edges)
  double close_up = 0.4;                    // frames: a magnified panel of the bed's lower
                                            // fraction of its height beside it (0: none)
  bool dark_background = false;
  int time_decimals = 2;  // "t = 7.32 s"
  // Multisample anti-aliasing of frames (1: none). Discs and text are anti-aliased in their
  // shaders anyway; 4x smooths the arrows too, but triples llvmpipe's cost of a 1280 x 720
  // frame (about 20 ms to 60 ms), so frames go without and the montage, one picture, with it.
  int samples = 1;
  int montage_samples = 4;
  // The viewer and lessons. A band over the beds kept for a caption (always, so the beds stay
  // put when captions come and go), the caption in it, a label over the whole bed (the regime
  // in words), and a zoomed bed panel.
  bool caption_band = false;
  std::string caption;
  std::string bed_label;
  BedZoom zoom;
};

// The gas arrows' reference speed for a scene blown at `superficial_velocity` (m/s): three times
// it, rounded up to 1, 2 or 5 x 10^k m/s, so that the arrows of any bed are seen (10 m/s for the
// paper's 2.8 m/s, 5 m/s for van Wachem's 0.9 m/s) and keep their length while the velocity
// changes in a run. 10 m/s without gas.
inline double gas_arrow_reference_for(double superficial_velocity) {
  if (!(superficial_velocity > 0.0)) return 10.0;
  const double want = 3.0 * superficial_velocity;
  double decade = std::pow(10.0, std::floor(std::log10(want)));
  for (;;) {
    for (double m : {1.0, 2.0, 5.0})
      if (m * decade >= want * (1.0 - 1e-12)) return m * decade;
    decade *= 10.0;
  }
}

// Colours by `c` over its own range: a range set for another quantity means nothing for it.
inline void set_colour_by(RenderSettings& rs, ColourBy c) {
  rs.colour_by = c;
  rs.range_min = rs.range_max = 0.0;
}

}  // namespace fluidbed::render
