// Kernels of the coupling and the gas: the porosity share of one particle (eq 22; inside a cell,
// across a face, across a corner) and one SIMPLE step of the gas on the paper's 15 x 45 grid
// through the porosity of a settled bed, with the jet at 2.8 m/s; then the gas step against the
// grid's size.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "cfd/gas_grid.hpp"
#include "cfd/gas_solver.hpp"
#include "coupling/coupler.hpp"
#include "coupling/porosity.hpp"
#include "per_unit.hpp"
#include "scene/settings.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {
namespace {

void BM_SphereCapVolume(benchmark::State& state) {
  double a = 0.0011;
  for (auto _ : state) {
    benchmark::DoNotOptimize(a);
    benchmark::DoNotOptimize(sphere_cap_volume(0.002, a));
  }
}
BENCHMARK(BM_SphereCapVolume);

void BM_SphereQuadrantVolume(benchmark::State& state) {
  double a = 0.0007, b = -0.0009;
  for (auto _ : state) {
    benchmark::DoNotOptimize(a);
    benchmark::DoNotOptimize(b);
    benchmark::DoNotOptimize(sphere_quadrant_volume(0.002, a, b));
  }
}
BENCHMARK(BM_SphereQuadrantVolume);

// One sphere (R = 2 mm) added to the cells it touches on the paper's grid (10 x 20 mm cells).
// Arg 0: inside one cell; 1: across a vertical face (two cells); 2: across a corner (four).
void BM_AddParticleVolume(benchmark::State& state) {
  const GasGrid g;  // 15 x 45 over 0.15 x 0.9 x 0.004 m
  std::vector<double> solid(static_cast<std::size_t>(g.cells()), 0.0);
  const double xs[3] = {0.055, 0.0505, 0.0505}, ys[3] = {0.11, 0.11, 0.1005};
  const auto k = static_cast<std::size_t>(state.range(0));
  double x = xs[k], y = ys[k];
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(y);
    add_particle_volume(g, x, y, 0.002, solid);
    benchmark::ClobberMemory();
  }
  state.SetLabel(k == 0 ? "inside a cell" : k == 1 ? "across a face" : "across a corner");
}
BENCHMARK(BM_AddParticleVolume)->Arg(0)->Arg(1)->Arg(2);

void BM_ParticleVolumeShares(benchmark::State& state) {
  const GasGrid g;
  VolumeShares shares;
  double x = 0.0505, y = 0.1005;  // a corner: four shares
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(particle_volume_shares(g, x, y, 0.002, shares));
    benchmark::DoNotOptimize(shares);
  }
}
BENCHMARK(BM_ParticleVolumeShares);

// The porosity of a bed that has fallen for 0.3 s (2400 spheres, DEM only): eq 22 per cell.
std::vector<double> settled_porosity(const GasGrid& g) {
  Settings s;
  s.scene.kind = SceneKind::Packing;
  Simulation sim(s);
  for (int k = 0; k < 20000; ++k) sim.step();
  const Particles& p = sim.dem().particles();
  std::vector<double> solid(static_cast<std::size_t>(g.cells()), 0.0), eps;
  for (std::size_t i = 0; i < p.size(); ++i)
    add_particle_volume(g, p.x[i], p.y[i], p.radius[i], solid);
  porosity_from_solid(g, solid, eps);
  return eps;
}

void BM_PorosityFromSolid(benchmark::State& state) {
  const GasGrid g;
  std::vector<double> solid(static_cast<std::size_t>(g.cells()), 1e-7), eps;
  for (auto _ : state) {
    porosity_from_solid(g, solid, eps);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * g.cells());
}
BENCHMARK(BM_PorosityFromSolid);

// The coupler's passes over the particles at each gas step, on one thread: the porosity and the
// drag summed per cell (Coupler::exchange), then each particle's drag frozen for the steps that
// follow (Coupler::freeze_drag), against the bed's width: N = 2,400 k spheres of 4 mm on a
// lattice (4.2 mm apart, numbered row by row) in a bed 0.15 k m wide on the paper's 10 x 20 mm
// cells, k = 1, 10, 100 (the 240,000-sphere bed's 1500 x 45 grid). The gas is at rest with the
// porosity of the lattice; the particles move at a few cm/s. Time per particle (s_per_unit).
// Second argument 1 (the widest bed only): 256 MB are written between the passes (untimed), as
// the gas step and the contacts of a run come between them, so that the passes start from a
// cold cache.
void BM_CouplerPasses(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const bool cold = state.range(1) != 0;
  std::vector<double> evict(cold ? (256u << 20) / sizeof(double) : 0, 0.0);
  const int k = static_cast<int>(n / 2400);
  GasGrid g;
  g.nx = 15 * k;
  g.width = 0.15 * k;
  Particles p;
  p.resize(n);
  const double pitch = 0.0042;
  const auto per_row = static_cast<std::size_t>(g.width / pitch);
  for (std::size_t i = 0; i < n; ++i) {
    p.set_sphere(i, 0.004, 2700.0);
    p.x[i] = 0.5 * pitch + pitch * static_cast<double>(i % per_row);
    p.y[i] = 0.5 * pitch + pitch * static_cast<double>(i / per_row);
    p.vx[i] = 0.03 * std::sin(0.7 * static_cast<double>(i));
    p.vy[i] = 0.03 * std::cos(1.3 * static_cast<double>(i));
  }
  Coupler coupler(g, CouplerParams{}, n);
  GasSolver gas(g, GasParams{});
  gas.set_porosity(coupler.compute_porosity(p, 0.0));
  coupler.refresh_cells(gas);
  coupler.freeze_drag(p);
  coupler.advance_drag(p, false);
  std::vector<double> fx, fy;
  double total_x = 0.0, total_y = 0.0;
  for (auto _ : state) {
    if (cold) {
      state.PauseTiming();
      for (double& v : evict) v += 1.0;
      benchmark::DoNotOptimize(evict.data());
      benchmark::ClobberMemory();
      state.ResumeTiming();
    }
    coupler.exchange(p, 0.0, fx, fy, total_x, total_y);
    coupler.freeze_drag(p);
    coupler.advance_drag(p, false);  // a drag to sum at the next exchange
    benchmark::ClobberMemory();
  }
  time_per_unit(state, static_cast<double>(n), cold ? "per particle and gas step, cold cache"
                                                    : "per particle and gas step");
}
BENCHMARK(BM_CouplerPasses)->Args({2400, 0})->Args({24000, 0})->Args({240000, 0})
    ->Unit(benchmark::kMicrosecond);
// The cold passes of the widest bed a fixed number of times: each writes 256 MB untimed first.
BENCHMARK(BM_CouplerPasses)->Args({240000, 1})->Iterations(40)->Unit(benchmark::kMicrosecond);

// Steps the gas `warmup` times through `eps` under the weight a fluidized bed would hand to it,
// F = (1 - eps)(rho_p - rho_f) g per cell (N/m^3, upward: its order of magnitude), then once per
// iteration of the benchmark's loop. Time per cell and SIMPLE iteration (s_per_unit); the label
// gives the SIMPLE iterations per step and the share of steps that rebuilt the preconditioner.
void time_gas_steps(benchmark::State& state, GasSolver& gas, const std::vector<double>& eps,
                    double dt, int warmup) {
  gas.set_porosity(eps);
  std::vector<double> fx(eps.size(), 0.0), fy(eps.size(), 0.0);
  for (std::size_t c = 0; c < eps.size(); ++c) fy[c] = (1.0 - eps[c]) * (2700.0 - 1.205) * 9.81;
  for (int k = 0; k < warmup; ++k) gas.step(dt, eps, fx, fy);
  std::int64_t iterations = 0, rebuilds = 0, solves = 0;
  for (auto _ : state) {
    const GasStepReport r = gas.step(dt, eps, fx, fy);
    iterations += r.simple_iterations;
    solves += r.pressure_iterations_total;
    rebuilds += r.preconditioner_rebuilt ? 1 : 0;
    benchmark::DoNotOptimize(r);
  }
  const double steps = static_cast<double>(state.iterations());
  char label[128];
  std::snprintf(label, sizeof label,
                "per cell and SIMPLE iteration; %.2f iterations per step, %.1f PCG iterations "
                "per iteration, %.1f %% rebuilt",
                static_cast<double>(iterations) / steps,
                static_cast<double>(solves) / static_cast<double>(iterations),
                100.0 * static_cast<double>(rebuilds) / steps);
  time_per_unit(state, static_cast<double>(eps.size()) * static_cast<double>(iterations) / steps,
                label);
}

// One gas step (SIMPLE, Crank-Nicolson, PCG pressure correction) at the paper's dt through the
// settled bed, the jet at U = 2.8 m/s (42 m/s in the slot), after 2000 steps of start-up.
void BM_GasStep(benchmark::State& state) {
  const GasGrid g;
  static const std::vector<double> eps = settled_porosity(g);
  GasParams params;  // the paper's air and jet
  GasSolver gas(g, params);
  time_gas_steps(state, gas, eps, 1.5e-5, 2000);
}
BENCHMARK(BM_GasStep)->Unit(benchmark::kMicrosecond);

// The gas step's cost per cell and SIMPLE iteration against the grid's size (issue 37, item 2:
// it should stay within 1.3 x from 675 cells to 67,500). Arguments {nx, 0}: the paper's bed
// (0.15 x 0.9 m) on nx x 3nx cells, from its 15 x 45 to 150 x 450, the grid of a study that
// refines; {nx, ny}: the paper's 10 x 20 mm cells on a wider bed (nx / 15 jets, one every
// 0.15 m, as wide.toml), up to the 240,000-sphere bed's 1500 x 45. The porosity is a bed's
// (0.45 below 0.25 m, 1 above, a row of cells between); 300 steps of start-up, then steps at
// the paper's CFL number with the preconditioner refreshed as in a run. A third argument names
// the pressure correction's preconditioner (1 banded, 2 multigrid; 0 or none: the automatic
// choice), to measure where one overtakes the other.
void BM_GasStepGrid(benchmark::State& state) {
  GasGrid g;
  g.nx = static_cast<int>(state.range(0));
  if (state.range(1) > 0) {
    g.ny = static_cast<int>(state.range(1));
    g.width = 0.01 * g.nx;
    g.height = 0.02 * g.ny;
  } else {
    g.ny = 3 * g.nx;
  }
  GasParams params;  // the paper's air, its jet at U = 2.8 m/s
  params.jets = std::max(1, static_cast<int>(std::lround(g.width / 0.15)));
  const auto method = state.range(2);
  if (method != 0)
    params.pressure_method = method == 1 ? PressureMethod::banded : PressureMethod::multigrid;
  GasSolver gas(g, params);
  std::vector<double> eps(static_cast<std::size_t>(g.cells()));
  for (int j = 0; j < g.ny; ++j) {
    const double y = (j + 0.5) * g.dy(), e = std::clamp((y - 0.25) / g.dy() + 0.5, 0.0, 1.0);
    for (int i = 0; i < g.nx; ++i) eps[static_cast<std::size_t>(g.index(i, j))] = 0.45 + 0.55 * e;
  }
  // The paper's step on its cells, shorter in proportion on finer ones: the same CFL number (a
  // 1 mm cell under the 42 m/s jet at 1.5e-5 s would pass 1).
  time_gas_steps(state, gas, eps, 1.5e-5 * std::min(1.0, g.dx() / 0.01), 300);
}
BENCHMARK(BM_GasStepGrid)
    ->Args({15, 0, 0})
    ->Args({30, 0, 0})
    ->Args({50, 0, 0})
    ->Args({80, 0, 0})
    ->Args({150, 0, 0})
    ->Args({150, 45, 0})
    ->Args({1500, 45, 0})
    ->Unit(benchmark::kMicrosecond);
// Each preconditioner forced, about where they cross and on the wide beds.
BENCHMARK(BM_GasStepGrid)
    ->ArgsProduct({{30, 40, 50, 65, 80}, {0}, {1, 2}})
    ->ArgsProduct({{150, 1500}, {45}, {1, 2}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fluidbed
