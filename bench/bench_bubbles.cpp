// Kernels of the bubble analysis (issue 15 point 7: under 5 % of a run's wall time at one frame
// per 10 ms of simulated time, i.e. a budget of a few ms per frame) on 2400 spheres of the
// paper's size: a packed hexagonal layer across the paper's bed with three holes (a jet cavity
// and two bubbles), 0.26 m deep, each sphere moved by up to 1 mm at random in x and y (half a
// cell: its place relative to the 2 mm cells is then uniform). The jitter matters: on the bare
// lattice every sphere's edge sits on a grid line and its shares cost half of what a sphere at
// a random place costs (about three quadrant volumes of three atan2 each), which is what a
// running bed has: 2400 spheres of the paper's bed at 2.8 m/s cost 1.2-1.4 ms per frame here.
//   BubbleVoidFraction        - the exact fine-grid void fraction (the library's choice), with
//                               its 10 mm window average;
//   BubbleVoidFractionKernel  - for the cost comparison only: a smooth kernel, each sphere's
//                               volume spread as the product of its exact x and y marginals
//                               (cap differences; no quadrant volumes; no window);
//   BubbleDetect              - connected regions, bed surface, jet cavity, centroids;
//   BubbleFrame               - one whole frame: void fraction, detection, tracking, summary
//                               (the hole positions alternate so that tracking has work).
// Counter: s_per_unit, labelled "per particle" (CPU time per sphere, printed with an SI prefix:
// 290n is 290 ns);
// the time per frame is the benchmark's own.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "analysis/bubbles.hpp"
#include "analysis/void_fraction.hpp"
#include "core/random.hpp"
#include "coupling/porosity.hpp"
#include "per_unit.hpp"

namespace fluidbed {
namespace {

constexpr double kD = 0.004;  // m

struct Hole {
  double x, y, radius;  // m
};

// 2400 spheres in hexagonal rows across 0.15 m, those within radius + d/2 of a hole's centre left
// out, rows added until the count is reached.
Particles bed_with_holes(double shift = 0.0) {
  const Hole holes[] = {
      {0.075, 0.0, 0.012}, {0.05, 0.09 + shift, 0.015}, {0.10, 0.16 + shift, 0.02}};
  const double r = 0.5 * kD;
  SplitMix64 rng(1);
  Particles p;
  p.resize(2400);
  std::size_t n = 0;
  for (int row = 0; n < p.size(); ++row) {
    const double y = r + row * kD * std::sqrt(3.0) / 2.0;
    for (int col = 0; n < p.size(); ++col) {
      const double x = r + (row % 2 == 1 ? r : 0.0) + col * kD;
      if (x + r > 0.15 + 1e-12) break;
      bool removed = false;
      for (const Hole& h : holes)
        if (std::hypot(x - h.x, y - h.y) < h.radius + r) removed = true;
      if (removed) continue;
      p.x[n] = x + 0.001 * (2.0 * rng.uniform() - 1.0);
      p.y[n] = y + 0.001 * (2.0 * rng.uniform() - 1.0);
      p.set_sphere(n, kD, 2700.0);
      ++n;
    }
  }
  return p;
}

void per_particle(benchmark::State& state, std::size_t n, const std::string& more = "") {
  time_per_unit(state, static_cast<double>(n), "per particle" + more);
}

void BM_BubbleVoidFraction(benchmark::State& state) {
  const Particles p = bed_with_holes();
  VoidFractionField f =
      make_void_fraction_field(make_fine_grid(0.15, 0.9, 0.004, 0.5 * kD, kD), 2.5 * kD);
  for (auto _ : state) {
    compute_void_fraction(p, f);
    benchmark::DoNotOptimize(f.eps.data());
    benchmark::ClobberMemory();
  }
  per_particle(state, p.size());
}
BENCHMARK(BM_BubbleVoidFraction)->Unit(benchmark::kMicrosecond);

// The smooth alternative: shares V fx(column) fy(row) from the exact marginals.
void add_sphere_separable(const FineGrid& g, double x, double y, double R,
                          std::vector<double>& solid) {
  const double volume = 4.0 / 3.0 * std::numbers::pi * R * R * R;
  const auto marginal = [&](double c, double h, int n, int& first, double* frac) {
    first = std::max(0, static_cast<int>(std::floor((c - R) / h)));
    const int last = std::min(n - 1, static_cast<int>(std::floor((c + R) / h)));
    double above_prev = volume;  // volume beyond the lower line of the current cell
    int k = 0;
    for (int i = first; i <= last; ++i, ++k) {
      const double above = i == last ? 0.0 : sphere_cap_volume(R, (i + 1) * h - c);
      frac[k] = (above_prev - above) / volume;
      above_prev = above;
    }
    return k;
  };
  double fx[12], fy[12];
  int i0, j0;
  const int nc = marginal(x, g.dx, g.nx, i0, fx);
  const int nr = marginal(y, g.dy, g.ny, j0, fy);
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c) solid[g.index(i0 + c, j0 + r)] += volume * fx[c] * fy[r];
}

void BM_BubbleVoidFractionKernel(benchmark::State& state) {
  const Particles p = bed_with_holes();
  const FineGrid g = make_fine_grid(0.15, 0.9, 0.004, 0.5 * kD, kD);
  std::vector<double> solid(static_cast<std::size_t>(g.cells()));
  for (auto _ : state) {
    std::fill(solid.begin(), solid.end(), 0.0);
    for (std::size_t i = 0; i < p.size(); ++i)
      add_sphere_separable(g, p.x[i], p.y[i], p.radius[i], solid);
    const double inv = 1.0 / (g.cell_area() * g.thickness);
    for (double& v : solid) v = 1.0 - v * inv;
    benchmark::DoNotOptimize(solid.data());
    benchmark::ClobberMemory();
  }
  per_particle(state, p.size());
}
BENCHMARK(BM_BubbleVoidFractionKernel)->Unit(benchmark::kMicrosecond);

void BM_BubbleDetect(benchmark::State& state) {
  const Particles p = bed_with_holes();
  const BubbleSettings s;
  const BedGeometry g;
  VoidFractionField f = make_void_fraction_field(
      make_fine_grid(g.width, g.height, g.thickness, s.cell_size, kD), s.window);
  compute_void_fraction(p, f);
  BubbleDetector detector(s, g);
  BubbleFrame frame;
  for (auto _ : state) {
    detector.detect(f, frame);
    benchmark::DoNotOptimize(frame.regions.data());
  }
  per_particle(state, p.size(), "; " + std::to_string(frame.regions.size()) + " regions");
}
BENCHMARK(BM_BubbleDetect)->Unit(benchmark::kMicrosecond);

void BM_BubbleFrame(benchmark::State& state) {
  const Particles a = bed_with_holes(0.0), b = bed_with_holes(0.004);
  BubbleAnalysis analysis({}, {});
  double t = 0.0;
  bool flip = false;
  for (auto _ : state) {
    t += 0.01;
    flip = !flip;
    benchmark::DoNotOptimize(analysis.analyse(t, flip ? a : b).regions.data());
  }
  per_particle(state, a.size());
}
BENCHMARK(BM_BubbleFrame)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fluidbed
