#include "coupling/void_fraction_smoothing.hpp"

#include <cstddef>

#include "core/errors.hpp"

namespace fluidbed {

VoidFractionSmoother::VoidFractionSmoother(const GasGrid& grid, double length)
    : nx_(grid.nx),
      ny_(grid.ny),
      transposed_(grid.nx > grid.ny),
      ldlt_(transposed_ ? grid.ny : grid.nx, transposed_ ? grid.nx : grid.ny),
      scratch_(static_cast<std::size_t>(grid.cells()), 0.0) {
  // The solver's grid: its rows of `fast` cells (the band's width) stacked `slow` high.
  const int fast = transposed_ ? ny_ : nx_, slow = transposed_ ? nx_ : ny_;
  const double d_fast = transposed_ ? grid.dy() : grid.dx();
  const double d_slow = transposed_ ? grid.dx() : grid.dy();
  const double a_fast = length * length / (d_fast * d_fast);
  const double a_slow = length * length / (d_slow * d_slow);
  const auto n = static_cast<std::size_t>(grid.cells());
  std::vector<double> diag(n, 1.0), east(n, 0.0), north(n, 0.0);
  for (int s = 0; s < slow; ++s) {
    for (int f = 0; f < fast; ++f) {
      const auto k = static_cast<std::size_t>(s * fast + f);
      // Each neighbour inside the domain couples by -a and adds a to the diagonal: the columns
      // sum to one (no flux through a wall).
      if (f + 1 < fast) {
        east[k] = -a_fast;
        diag[k] += a_fast;
        diag[k + 1] += a_fast;
      }
      if (s + 1 < slow) {
        north[k] = -a_slow;
        diag[k] += a_slow;
        diag[k + static_cast<std::size_t>(fast)] += a_slow;
      }
    }
  }
  // Diagonally dominant with a positive diagonal: always positive definite.
  if (!ldlt_.factorize(diag.data(), east.data(), north.data()))
    throw SimulationFailure("the void fraction's smoothing matrix is not positive definite");
}

void VoidFractionSmoother::apply(std::vector<double>& v) const {
  if (!transposed_) {
    ldlt_.solve(v.data(), v.data());
    return;
  }
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      scratch_[static_cast<std::size_t>(i * ny_ + j)] = v[static_cast<std::size_t>(j * nx_ + i)];
  ldlt_.solve(scratch_.data(), scratch_.data());
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      v[static_cast<std::size_t>(j * nx_ + i)] = scratch_[static_cast<std::size_t>(i * ny_ + j)];
}

}  // namespace fluidbed
