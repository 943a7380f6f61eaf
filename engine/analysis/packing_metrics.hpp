#pragma once
// Measures of a packed or settled bed, as the peers (LIGGGHTS, LAMMPS) were measured:
//   bed height     - the mean, over columns 1 cm wide across the bed, of the highest particle
//                    centre in each column;
//   solid fraction - the volume of the spheres whose centres lie between 0.02 m and
//                    bed_height - 0.03 m, over that slab's volume (width x thickness x height);
//   bed top        - the height of the highest sphere centre (what Lethe and van Wachem et al.
//                    compare with the experiment's bed height: higher than the column mean).
#include "dem/particles.hpp"

namespace fluidbed {

struct PackingMetrics {
  double bed_height = 0.0;      // m
  double solid_fraction = 0.0;  // -
};

PackingMetrics measure_packing(const Particles& p, double width, double thickness);

// m: the highest centre's y (0 without particles).
double bed_top(const Particles& p);

}  // namespace fluidbed
