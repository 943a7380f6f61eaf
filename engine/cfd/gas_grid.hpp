#pragma once
// The gas grid: uniform cells over the bed (the paper: 15 x 45 cells of 10 mm x 20 mm), one
// cell deep (dz = the slab thickness, eq 23). Cells are numbered c = j * nx + i, i along x
// (left to right), j along y (bottom to top). Shared by the gas solver and the coupler. With a
// plenum the grid reaches below the particles' floor (bottom < 0): height is the gas's, floor
// to top plus the plenum.
#include <algorithm>

namespace fluidbed {

struct GasGrid {
  int nx = 15;           // cells across
  int ny = 45;           // cells up
  double width = 0.15;   // m
  double height = 0.9;   // m
  double depth = 0.004;  // m, slab thickness
  // m: the height of the grid's bottom in the particles' frame (whose floor is y = 0): minus the
  // plenum's height (inlet.plenum_height), 0 without one. Positions given to the grid are in the
  // particles' frame; the gas solver works in cell indices and never needs it.
  double bottom = 0.0;

  double dx() const { return width / nx; }
  double dy() const { return height / ny; }
  double cell_volume() const { return dx() * dy() * depth; }  // eq 23
  int cells() const { return nx * ny; }
  int index(int i, int j) const { return j * nx + i; }
  // Column and row of the cell holding (x, y); points outside are clamped to the edge cells.
  int column(double x) const { return along(x, dx(), nx); }
  int row(double y) const { return along(y - bottom, dy(), ny); }
  // The cell of coordinate x along a side of n cells of size d (loops hoist d = dx() or dy()).
  static int along(double x, double d, int n) {
    return static_cast<int>(std::clamp(x / d, 0.0, n - 1.0));
  }
  int cell_of(double x, double y) const { return index(column(x), row(y)); }
};

}  // namespace fluidbed
