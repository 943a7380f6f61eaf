// Kernels of the particle step: the contact law, a neighbour-grid rebuild, one full step of the
// packed bed.
#include <benchmark/benchmark.h>

#include "dem/cell_grid.hpp"
#include "dem/contact_law.hpp"
#include "scene/settings.hpp"
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

}  // namespace
}  // namespace fluidbed

BENCHMARK_MAIN();
