#pragma once
// Lacey's mixing index of two kinds of particle (model.md 6):
//   M = (s0^2 - s^2) / (s0^2 - sr^2),  s0^2 = p (1 - p),  sr^2 = p (1 - p) / n,
// p the fraction of kind 1, s^2 the variance of the fraction of kind 1 over the sample cells, n
// the mean number of particles per sample cell. M = 0 when every cell holds one kind
// (segregated), about 1 for a random arrangement.
//
// Sample cells: squares of cell_size (default 0.02 m, 5 diameters of the paper's particle: a
// packed cell holds about 25 spheres, so that sr^2 is a few per cent of s0^2, while the paper's
// bed, 0.15 x 0.2 m, still has 8 columns and 10 rows of them to resolve the two layers), over the
// domain, nx = round(width / cell_size) columns so that they cover the width exactly. Cells with
// fewer than min_particles spheres (the surface, the freeboard, the jet) are left out: a cell of
// two particles says little about mixing and would dominate s^2. s^2 is the variance over the
// cells weighted by their particle counts, s^2 = sum n_c (x_c - p)^2 / sum n_c, with p the
// fraction over the counted particles: for a random arrangement its expectation is
// p (1 - p) / n with n the mean count per cell, which is the sr^2 above, so M stays near 1 for a
// random set whatever the cells' fill.
#include <cstdint>
#include <vector>

#include "dem/particles.hpp"

namespace fluidbed {

struct LaceySettings {
  double cell_size = 0.02;  // m, side of a square sample cell
  int min_particles = 5;    // cells holding fewer are not counted
};

// Kind 1 for the upper half of the particles by initial height, 0 for the lower half: the
// particles sorted by (y, index), the first floor(N / 2) are kind 0. Equal halves (p = 1/2 for
// an even count) whatever the packing's layering; ties broken by index (deterministic).
std::vector<std::uint8_t> kinds_by_initial_height(const std::vector<double>& y);

struct LaceyResult {
  bool ok = false;             // false: no cell counted or only one kind present
  double index = 0.0;          // M, -
  double p = 0.0;              // fraction of kind 1 over the counted particles
  double s2 = 0.0;             // variance of the kind-1 fraction over the cells
  double s0_2 = 0.0;           // p (1 - p)
  double sr_2 = 0.0;           // p (1 - p) / n
  double mean_per_cell = 0.0;  // n
  int cells = 0;               // counted
  int particles = 0;           // in counted cells
};

// kind has one entry per particle (0 or 1). Throws InputError naming `mixing.cell_size` or
// `mixing.min_particles` for impossible settings.
LaceyResult lacey_index(const Particles& p, const std::vector<std::uint8_t>& kind, double width,
                        double height, const LaceySettings& s = {});

}  // namespace fluidbed
