#pragma once
// The void fraction smoothed over a length L (`coupling.void_fraction = "smoothed"`): each gas
// cell's exact share of the spheres' volume (eq 22, coupling/porosity.hpp) is replaced by the
// solution s of
//   s - L^2 laplacian(s) = s_exact,
// with no flux through any side of the domain, discretised on the gas cells (five points, the
// cell sizes dx and dy). This is the smoothing Lethe's void fraction applies with its "l2
// smoothing length" (its van Wachem example: 1.5 mm); in one dimension and on a fine grid its
// kernel is exp(-|x| / L) / (2 L), so a sphere's volume spreads over a few L. The operator's
// columns sum to one, so the spheres' total volume is kept to round-off, and a uniform field is
// left as it is. L of a tenth of a cell or less changes almost nothing; L of a cell or more
// removes the cell-to-cell noise of cells of two or three diameters.
//
// The matrix depends only on the grid and L: it is factorized once (cfd/banded_ldlt.hpp, the band
// along the grid's shorter side), and each gas step costs two triangular solves, about
// 4 cells x min(nx, ny) multiply-adds (0.2 ms on 27 x 150 cells). The solve runs in a fixed
// order: the same bits for any thread count.
#include <vector>

#include "cfd/banded_ldlt.hpp"
#include "cfd/gas_grid.hpp"

namespace fluidbed {

class VoidFractionSmoother {
 public:
  // length > 0 (m).
  VoidFractionSmoother(const GasGrid& grid, double length);

  // Replaces the per-cell field v (the grid's cells, c = j * nx + i) by its smoothed form.
  void apply(std::vector<double>& v) const;

 private:
  int nx_, ny_;
  bool transposed_;  // the band runs along y (nx > ny): cells renumbered i * ny + j
  BandedLdlt ldlt_;
  mutable std::vector<double> scratch_;
};

}  // namespace fluidbed
