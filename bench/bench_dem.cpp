// Kernels of the particle step: the contact law, a neighbour-grid rebuild, one full step of the
// packed bed, the step of a wide bed by the particles' numbering, and a monolayer's step
// against a thick slab's.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <string>

#include "per_unit.hpp"
#include "core/permute.hpp"
#include "dem/cell_grid.hpp"
#include "dem/contact_law.hpp"
#include "scene/settings.hpp"
#include "sim/model_params.hpp"
#include "sim/placement.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {
namespace {

void BM_ContactForce(benchmark::State& state) {
  const ContactParams p{50000.0, 50000.0, 0.15, 0.15, 0.3};
  double dt = 1e-7, dn = 1e-6, vn = 0.1, vt = 0.02;
  for (auto _ : state) {
    benchmark::DoNotOptimize(dn);
    benchmark::DoNotOptimize(vn);
    const ContactForce f = contact_force(p, dn, dt, vn, vt);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_ContactForce);

// A bed that has fallen for a while (particles in contact), shared by the benchmarks below.
Simulation& settled_bed() {
  static Simulation* sim = [] {
    Settings s;
    s.scene.kind = SceneKind::Packing;
    auto* p = new Simulation(s);
    for (int k = 0; k < 20000; ++k) p->step();
    return p;
  }();
  return *sim;
}

void BM_NeighbourGridBuild(benchmark::State& state) {
  const Particles& p = settled_bed().dem().particles();
  CellGrid grid;
  grid.configure(0.15, 0.9, 0.004);
  for (auto _ : state) {
    grid.build(p.x, p.y, p.radius);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(p.size()));
}
BENCHMARK(BM_NeighbourGridBuild);

void BM_ParticleStep2400(benchmark::State& state) {
  Simulation& sim = settled_bed();
  for (auto _ : state) sim.step();
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sim.particle_count()));
}
BENCHMARK(BM_ParticleStep2400);

// The particle step (no gas, one thread) of N spheres from the wide bed's lattice start (wide.toml
// at the paper's fill: a bed 0.15 m wide per 2,400), by how the particles are numbered: 0 along
// the lattice's strips (as placed), 1 shuffled (a bed mixed as much as it can be), 2 shuffled and
// renumbered by cell (contact.renumber_steps; its first renumbering before the timing). Time per
// particle-step (s_per_unit).
void BM_ParticleNumbering(benchmark::State& state) {
  const auto n = static_cast<int>(state.range(0));
  const auto mode = state.range(1);
  Settings s;
  s.particles.count = n;
  s.domain.width = 0.15 * n / 2400.0;
  Particles p = place_particles(s);
  if (mode > 0) {
    std::vector<std::int32_t> order(p.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(1));
    for (auto* v : p.all_arrays()) gather_by(*v, order);
  }
  DemParams d = dem_params_for(s);
  d.threads = 1;
  d.renumber_steps = mode == 2 ? 1000 : 0;
  DemSolver dem(d, std::move(p));
  dem.step();  // the first neighbour list (and the renumbering) untimed
  for (auto _ : state) dem.step();
  const char* how[] = {"along strips", "at random", "at random, then renumbered by cell"};
  time_per_unit(state, static_cast<double>(n),
                std::string("per particle-step, numbered ") + how[mode]);
}
BENCHMARK(BM_ParticleNumbering)
    ->ArgsProduct({{24000, 240000}, {0, 1, 2}})
    ->Iterations(100)
    ->Unit(benchmark::kMillisecond);

// The particle step (no gas, one thread) of the packing's 2,400 spheres from the lattice start
// (the slab bench's work, `fluidbed bench --peer liggghts`) after 0.15 s of fall, in contact:
// 0 a monolayer, 1 a thick slab three diameters deep (domain.thickness = 0.012: the front and
// back walls, the 3D law, six degrees of freedom). Time per particle-step (s_per_unit).
void BM_ParticleStepDepth(benchmark::State& state) {
  const bool slab = state.range(0) == 1;
  Settings s;
  if (slab) s.domain.thickness = 0.012;
  DemParams d = dem_params_for(s);
  d.threads = 1;
  DemSolver dem(d, place_particles(s));
  const auto fall = static_cast<int>(0.15 / d.dt);
  for (int k = 0; k < fall; ++k) dem.step();
  for (auto _ : state) dem.step();
  time_per_unit(
      state, static_cast<double>(dem.particles().size()),
      slab ? "per particle-step, a thick slab (0.012 m)" : "per particle-step, a monolayer");
}
BENCHMARK(BM_ParticleStepDepth)->Arg(0)->Arg(1)->Iterations(5000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fluidbed

BENCHMARK_MAIN();
