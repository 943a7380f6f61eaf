#pragma once
// Eq 22: the porosity of a gas cell, eps = 1 - (solid volume in the cell) / dV, with the exact
// share of each sphere that lies inside the cell.
//
// Geometry of the slab: sphere centres lie on the mid-plane and the slab is one diameter thick,
// so no sphere is cut in z; in x-y a sphere is smaller than a cell (D = 4 mm, cells 10 x 20 mm),
// so it is cut by at most one vertical and one horizontal grid line. Its shares are then a
// spherical cap (one line) or caps and one "double cap" (two lines), all in closed form below.
#include <vector>

#include "cfd/gas_grid.hpp"

namespace fluidbed {

// Volume of the part x > a of a sphere of radius R centred at the origin (a cap; any a:
// 0 for a >= R, the whole sphere for a <= -R).
double sphere_cap_volume(double R, double a);

// Volume of the part x > a, y > b of a sphere of radius R centred at the origin (any signs of
// a and b, |a| or |b| >= R included). Closed form, with w = sqrt(R^2 - a^2 - b^2), inside the
// disc a^2 + b^2 < R^2 (valid there for every sign of a and b):
//   V = [ 2 R^3 atan2(R w, a b) - a (3R^2 - a^2) atan2(w, b) - b (3R^2 - b^2) atan2(w, a)
//         + 2 a b w ] / 3
// Outside the disc at most one plane cuts the part of the sphere in the quadrant: 0, a cap, or
// the sphere less two disjoint caps. Absolute error about 3e-15 of the sphere's volume (the
// terms cancel when the quadrant holds a sliver of the sphere).
double sphere_quadrant_volume(double R, double a, double b);

// True when a sphere of radius R fits in one cell in both directions (2R <= dx and 2R <= dy):
// the condition under which add_particle_volume's one-line-per-direction split is exact.
inline bool sphere_fits_cells(const GasGrid& g, double R) {
  return 2.0 * R <= g.dx() && 2.0 * R <= g.dy();
}

// The shares of one sphere's volume in the cells it touches (at most four).
struct VolumeShares {
  int count = 0;
  int cell[4] = {0, 0, 0, 0};
  double volume[4] = {0.0, 0.0, 0.0, 0.0};  // m^3
};

// Fills `out` with the sphere's shares (the split add_particle_volume uses); returns the count.
int particle_volume_shares(const GasGrid& g, double x, double y, double R, VolumeShares& out);

// The same for spheres [0, n) at once, in two passes: share_geometry finds each sphere's cell,
// the lines it crosses and the caps beyond them (branch-free arithmetic over arrays, which
// vectorises), shares_from_geometry splits the volume (the double cap of a corner, about one
// sphere in twelve in the paper's bed, only there). The results are particle_volume_shares'
// to the bit.
struct ShareGeometry {
  std::vector<int> cell, step_x, step_y;  // step: -1, 0 (no line crossed) or 1 cell
  std::vector<double> a_x, a_y;           // m, distance from the centre to the line crossed
  std::vector<double> cap_x, cap_y;       // m^3, the sphere's part beyond it
  void resize(std::size_t n);
};
void share_geometry(const GasGrid& g, std::size_t n, const double* x, const double* y,
                    const double* R, ShareGeometry& out);
int shares_from_geometry(const GasGrid& g, const ShareGeometry& geo, std::size_t i, double R,
                         VolumeShares& out);

// Adds the volume of the sphere (radius R, centre (x, y)) to each cell it touches: 1, 2 or 4
// cells, split by the nearer vertical and horizontal line of the cell holding the centre
// (precondition: sphere_fits_cells). A line that is an outer wall does not split: a part of the
// sphere beyond a wall (a small overlap) stays in the edge cell, so the shares always sum to the
// sphere's volume. solid_volume has g.cells() entries (m^3); no allocation. Cost on the
// development machine: about 8 ns inside one cell (no transcendental), 10 ns across a face (a
// cap: a polynomial), 60 ns across a corner (one sqrt, three atan2).
void add_particle_volume(const GasGrid& g, double x, double y, double R,
                         std::vector<double>& solid_volume);

// eps = 1 - solid / dV per cell (eq 22). eps is resized to solid_volume's size. No clamping:
// a cell over-filled by overlapping spheres shows a low or negative eps, the caller decides.
void porosity_from_solid(const GasGrid& g, const std::vector<double>& solid_volume,
                         std::vector<double>& eps);

}  // namespace fluidbed
