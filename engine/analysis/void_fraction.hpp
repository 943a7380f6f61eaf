#pragma once
// The void fraction on a fine grid (model.md 6): eps = 1 - (solid volume in a cell) / (cell
// area x slab thickness), with cells of about half a particle diameter, fine enough to see a
// bubble's shape, independent of the gas grid (10 x 20 mm cells in the paper's bed).
//
// Each sphere's volume is shared exactly among the cells it covers. A sphere of 4 mm on cells of
// 2 mm spans 2 or 3 columns and rows (4 when the cell is smaller than a radius): its share in a
// cell is the volume between two vertical and two horizontal lines, which inclusion-exclusion
// writes with Q(a, b), the volume of the part x > a, y > b (coupling/porosity.hpp's
// sphere_quadrant_volume; sphere_cap_volume where one line is absent):
//   V(cell) = Q(x0, y0) - Q(x1, y0) - Q(x0, y1) + Q(x1, y1).
// Q is needed once per grid-line crossing inside the sphere's span (up to 4 on 2 mm cells).
//
// Exact rather than a smooth kernel: measured with bench_bubbles.cpp (2400 spheres at random
// places relative to the cells, the development machine's 2 cores shared with other work), the
// exact shares and the window average cost about 350 ns of CPU per sphere, 0.85 ms per frame
// (on frames of the paper's bed at 2.8 m/s: 1.3 ms; about three quadrant volumes per sphere,
// whose three atan2 are 40 % of the time), against 60 ns (0.14 ms) for the cheapest smooth
// kernel, the product of the sphere's exact x and y marginals (cap differences only). Both fit
// a frame's budget: one frame per 10 ms of simulated time, which takes 50-150 ms of wall time,
// so 5 % is 2.5-7.5 ms. The kernel, though, misplaces up to 3.8 % of a sphere's volume between
// cells, 0.08 in a cell's eps: as much as the margin between a bubble's boundary cells and the
// threshold. Exact shares give the packed layer its true eps (0.395 for a hexagonal one) and
// put a bubble's edge where the spheres are, so the threshold of 0.8 means what model.md says.
//
// A sphere's parts beyond a wall (a small overlap) stay in the edge cell, as in porosity.hpp, so
// the shares always sum to the sphere's volume; a centre outside the domain (a particle thrown
// above the top) counts in the nearest edge cells. Sums run in particle order (deterministic).
// Thick slabs (model.md 7) are handled as well: the share of a sphere lying wholly inside the
// slab does not depend on its z.
#include <vector>

#include "dem/particles.hpp"

namespace fluidbed {

// The fine grid over the domain (width x height, left wall at x = 0, bottom at y = 0): nx
// columns and ny rows of equal cells, nx = round(width / cell_size) (at least 1) so that the
// cells cover the width exactly; likewise in y. Cells are then square to within a few per cent.
struct FineGrid {
  int nx = 0, ny = 0;
  double dx = 0.0, dy = 0.0;  // m, cell size
  double thickness = 0.0;     // m, slab depth (z)

  int cells() const { return nx * ny; }
  int index(int i, int j) const { return i + nx * j; }     // row-major, j = 0 at the bottom
  double x_centre(int i) const { return (i + 0.5) * dx; }  // m
  double y_centre(int j) const { return (j + 0.5) * dy; }  // m
  double cell_area() const { return dx * dy; }             // m^2
  double width() const { return nx * dx; }                 // m
  double height() const { return ny * dy; }                // m
};

// Throws InputError naming `bubbles.cell_size` unless 0 < cell_size <= min(width, height) and
// cell_size >= particle_diameter / 8 (finer grids than that cost more than they show: a sphere
// would span 9 x 9 cells or more).
FineGrid make_fine_grid(double width, double height, double thickness, double cell_size,
                        double particle_diameter);

// The field, two ways, both exact (eq 22 with the sphere shares above):
//   eps        - per fine cell;
//   eps_window - over a square sample window of (2 half_window + 1) cells a side centred on each
//                fine cell (clipped at the domain's walls: the part of the window inside). With
//                cells of half a diameter, eps alone resolves single spheres: a dilute region
//                of eps 0.85 (a bubble with particles raining through it) reads as a sieve of
//                dense cells, one per sphere, and its "bubble" breaks into fragments. The window
//                (2.5 d by default: 10 mm, 5 cells, the gas grid's width) averages over a few
//                spheres while keeping the fine grid's 2 mm steps for the boundary: one sphere in
//                a window of 10 x 10 mm leaves eps = 0.92, two 0.83, three 0.75. The window
//                average of the exact cell shares is the exact volume in the window.
// Rows from top_row up hold no solid (eps = 1): the bubble detector skips the empty freeboard.
struct VoidFractionField {
  FineGrid grid;
  int half_window_x = 0, half_window_y = 0;  // cells on either side of the window's centre
  std::vector<double> eps;                   // -, grid.cells() entries (FineGrid::index)
  std::vector<double> eps_window;            // -, grid.cells() entries
  int top_row = 0;                           // one past the highest row a sphere reaches
  std::vector<double> scratch;               // working space of compute_void_fraction

  double at(int i, int j) const { return eps[grid.index(i, j)]; }
  double window_at(int i, int j) const { return eps_window[grid.index(i, j)]; }
};

// A field on `grid` with a sample window of side `window` (m), rounded to an odd number of
// cells in each direction (window <= one cell: no averaging). Throws InputError naming
// `bubbles.window` unless 0 <= window <= min(width, height).
VoidFractionField make_void_fraction_field(const FineGrid& grid, double window);

// Adds the exact shares of one sphere (centre (x, y), radius R) to solid (m^3 per cell,
// grid.cells() entries). No allocation.
void add_sphere_to_fine_grid(const FineGrid& grid, double x, double y, double R,
                             std::vector<double>& solid);

// eps and eps_window of every cell from the particles' positions and radii (the arrays are
// sized on the first call and reused after). No clamping: a cell over-filled by overlapping
// spheres shows eps a little below the packing limit, never a bubble.
void compute_void_fraction(const Particles& p, VoidFractionField& field);

}  // namespace fluidbed
