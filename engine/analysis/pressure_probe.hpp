#pragma once
// The gas pressure at a point, as a pressure probe in the wall of a bed reads it against the
// outlet (diagnostics.probes): bilinear between the four cell centres around the point, minus
// the mean pressure of the top row of cells. A point between a wall and the nearest row or
// column of centres takes that row's or column's value (the interpolation is clamped to the
// centres, not extrapolated to the wall).
#include <vector>

#include "cfd/gas_grid.hpp"

namespace fluidbed {

// Pa: p at (x, y) (m) minus the mean over the top row of cells; p holds the cell-centre
// pressures of `grid` (GasSolver::pressure(), c = j * nx + i).
double probe_pressure(const GasGrid& grid, const std::vector<double>& p, double x, double y);

}  // namespace fluidbed
