#include "sim/snapshot.hpp"

#include "sim/simulation.hpp"

namespace fluidbed {

void take_snapshot(const Simulation& sim, Snapshot& out) {
  const Settings& s = sim.settings();
  const DemSolver& dem = sim.dem();
  const Particles& p = dem.particles();
  out.time = sim.time();
  out.step = sim.steps();
  out.dt = s.time.dt;
  out.width = s.domain.width;
  out.height = s.domain.height;
  out.thickness = s.domain.thickness;
  out.top_wall = s.domain.top_wall;
  out.dp = sim.pressure_drop();
  out.max_overlap_ratio = dem.diagnostics().max_overlap_ratio;
  out.kinetic_energy = dem.diagnostics().kinetic_energy;
  out.contacts = dem.diagnostics().pair_contacts + dem.diagnostics().wall_contacts;
  out.x = p.x;
  out.y = p.y;
  out.radius = p.radius;
  out.vx = p.vx;
  out.vy = p.vy;
  out.spin = p.w;
  out.fx = p.fx;
  out.fy = p.fy;
  out.torque = p.torque;
  out.overlap = dem.particle_overlap();
  out.initial_y = sim.initial_heights();
  if (const GasSolver* g = sim.gas()) {
    out.inlet_kind = s.inlet.kind;
    out.jet_width = s.inlet.jet_width;
    out.jets = s.inlet.jets;
    out.superficial_velocity = g->superficial_velocity();
    out.jet_velocity = g->jet_velocity();
    out.nx = g->grid().nx;
    out.ny = g->grid().ny;
    const auto cells = static_cast<std::size_t>(g->grid().cells());
    out.gas_ux.resize(cells);
    out.gas_uy.resize(cells);
    for (std::size_t c = 0; c < cells; ++c) g->cell_velocity(static_cast<int>(c), out.gas_ux[c], out.gas_uy[c]);
    out.porosity = g->porosity();
    out.pressure = g->pressure();
  } else {
    out.inlet_kind = InletKind::None;
    out.nx = out.ny = 0;
    out.gas_ux.clear();
    out.gas_uy.clear();
    out.porosity.clear();
    out.pressure.clear();
  }
}

std::shared_ptr<Snapshot> SnapshotChannel::acquire() {
  std::lock_guard lock(mutex_);
  // Reuse the spare buffer when no reader still holds it. use_count() alone is a relaxed load: it
  // would not order the last reader's reads before our writes (a data race, which the thread
  // sanitizer reports). Copying the pointer first is an acquire-release on the same count, after
  // the reader's release of it. Readers cannot take the spare again (they get latest_ only).
  if (spare_) {
    std::shared_ptr<Snapshot> probe = spare_;
    if (probe.use_count() == 2) {
      probe.reset();
      return std::move(spare_);
    }
  }
  return std::make_shared<Snapshot>();
}

void SnapshotChannel::publish(std::shared_ptr<Snapshot> s) {
  std::lock_guard lock(mutex_);
  spare_ = std::move(latest_);
  latest_ = std::move(s);
  sequence_.fetch_add(1, std::memory_order_release);
}

std::shared_ptr<const Snapshot> SnapshotChannel::latest(std::uint64_t* sequence) const {
  std::lock_guard lock(mutex_);
  if (sequence) *sequence = sequence_.load(std::memory_order_relaxed);
  return latest_;
}

}  // namespace fluidbed
