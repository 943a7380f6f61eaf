// The pressure correction's cost against the grid's size (issue 37, item 2: a solver of linear
// cost is wanted where today's banded factorization grows faster than the grid). Grids of the
// paper's shape, three cells high per cell wide, from 675 cells (15 x 45, the paper's bed) to
// 67,500 (150 x 450): per solve with the factorization kept (what most SIMPLE iterations pay),
// and per refactorization (paid when a coefficient has moved by more than
// gas.preconditioner_refresh). Time per cell (s_per_unit), so that a cost growing with the grid
// shows as a growing number. The coefficients are a bed's on the paper's cells, twice as tall as
// wide: a face's coefficient is its area squared over the momentum diagonal (a volume), so the
// vertical faces' are (dy / dx)^2 = 4 times the horizontal ones'; each varies by +- 20 % from cell
// to cell (the porosity's variation). The kept factorization is made from coefficients 5 % away
// (a refresh of 0.1 keeps factorizations up to 10 % away), the right-hand side a smooth field with
// a jet-like peak.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "cfd/pressure_solver.hpp"
#include "per_unit.hpp"

namespace fluidbed {
namespace {

// Deterministic coefficients: 2 and 0.5 times 1 + 0.2 sin-like patterns, shifted by `shift`
// (relative).
void fill(PressureSolver& p, int nx, int ny, double shift) {
  auto& cu = p.coefficients_u();
  auto& cv = p.coefficients_v();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i)
      cu[static_cast<std::size_t>(j * (nx + 1) + i)] =
          (i == 0 || i == nx) ? 0.0
                              : 2.0 * (1.0 + 0.2 * std::sin(0.7 * i + 1.3 * j)) * (1.0 + shift);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i)
      cv[static_cast<std::size_t>(j * nx + i)] =
          j == 0 ? 0.0 : 0.5 * (1.0 + 0.2 * std::cos(1.1 * i + 0.5 * j)) * (1.0 - shift);
}

std::vector<double> rhs(int nx, int ny) {
  std::vector<double> b(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5) / nx - 0.5, y = (j + 0.5) / ny;
      b[static_cast<std::size_t>(j * nx + i)] = std::exp(-200.0 * x * x) * (1.0 - y) + 0.1 * y;
    }
  return b;
}

// Arguments: the grid's width in cells (3 times as many rows), or width and height.
int rows(const benchmark::State& state) {
  return state.range(1) > 0 ? static_cast<int>(state.range(1))
                            : 3 * static_cast<int>(state.range(0));
}

// Every benchmark's grids: the paper's shape from 15 x 45 to 150 x 450, then wide beds of the
// paper's cells up to the 240,000-sphere bed's 1500 x 45.
void grids(benchmark::internal::Benchmark* b) {
  for (int nx : {15, 30, 50, 65, 80, 90, 150}) b->Args({nx, 0});
  for (int nx : {150, 500, 1500}) b->Args({nx, 45});
  b->Unit(benchmark::kMicrosecond);
}

void solve_kept(benchmark::State& state, PressureMethod method) {
  const int nx = static_cast<int>(state.range(0)), ny = rows(state);
  PressureSolver p(nx, ny, method);
  fill(p, nx, ny, 0.05);
  p.update_preconditioner(0.0);  // factorized 5 % away from what is solved
  fill(p, nx, ny, 0.0);
  const std::vector<double> b = rhs(nx, ny);
  std::vector<double> x(b.size());
  std::int64_t iterations = 0;
  for (auto _ : state) {
    const PressureSolveReport r = p.solve(b.data(), x.data(), 1e-3, 0.0, 200);
    iterations += r.iterations;
    benchmark::DoNotOptimize(x.data());
  }
  char label[64];
  std::snprintf(label, sizeof label, "per cell; %.1f PCG iterations",
                static_cast<double>(iterations) / static_cast<double>(state.iterations()));
  time_per_unit(state, static_cast<double>(nx) * ny, label);
}

void BM_PressureSolveKept(benchmark::State& state) {
  solve_kept(state, PressureMethod::banded);
}
BENCHMARK(BM_PressureSolveKept)->Apply(grids);

void BM_PressureSolveMultigrid(benchmark::State& state) {
  solve_kept(state, PressureMethod::multigrid);
}
BENCHMARK(BM_PressureSolveMultigrid)->Apply(grids);

void refactorize(benchmark::State& state, PressureMethod method) {
  const int nx = static_cast<int>(state.range(0)), ny = rows(state);
  PressureSolver p(nx, ny, method);
  double shift = 0.0;
  for (auto _ : state) {
    shift = shift == 0.0 ? 0.05 : 0.0;
    fill(p, nx, ny, shift);
    benchmark::DoNotOptimize(p.update_preconditioner(0.0));
  }
  time_per_unit(state, static_cast<double>(nx) * ny, "per cell");
}

void BM_PressureRefactorize(benchmark::State& state) {
  refactorize(state, PressureMethod::banded);
}
BENCHMARK(BM_PressureRefactorize)->Apply(grids);

void BM_PressureRebuildMultigrid(benchmark::State& state) {
  refactorize(state, PressureMethod::multigrid);
}
BENCHMARK(BM_PressureRebuildMultigrid)->Apply(grids);

}  // namespace
}  // namespace fluidbed
