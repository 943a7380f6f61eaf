#include "sim/snapshot.hpp"

#include <array>
#include <cstring>
#include <utility>

#include "sim/simulation.hpp"

namespace fluidbed {

namespace {
// Version 3 adds a thick bed's velocity and force across the slab, spin and torque about x and
// y; version 2 (a checkpoint written before them) loads with those empty. Version 4 adds the gas
// grid's bottom (a plenum); versions 2 and 3 load with 0.
constexpr char kSnapshotTag[8] = {'F', 'L', 'B', 'S', 'N', 'A', 'P', '4'};
constexpr std::size_t kTagVersion = sizeof kSnapshotTag - 1;

// Snapshot or const Snapshot: pointers to its vectors across the slab, in file order.
template <class S>
auto depth_vectors(S& s) {
  return std::array{&s.vz, &s.fz, &s.spin_x, &s.spin_y, &s.torque_x, &s.torque_y};
}
}  // namespace

void save_snapshot(std::ostream& out, const Snapshot& s) {
  out.write(kSnapshotTag, sizeof kSnapshotTag);
  for (double v : {s.time, s.dt, s.width, s.height, s.thickness, s.jet_width,
                   s.superficial_velocity, s.jet_velocity, s.dp, s.max_overlap_ratio,
                   s.kinetic_energy, s.void_dx, s.void_dy})
    put(out, v);
  put(out, s.step);
  for (int v : {static_cast<int>(s.top_wall), static_cast<int>(s.inlet_kind), s.jets, s.contacts,
                s.nx, s.ny, s.void_nx, s.void_ny})
    put(out, static_cast<std::int32_t>(v));
  for (const std::vector<double>* v :
       {&s.x, &s.y, &s.radius, &s.vx, &s.vy, &s.spin, &s.fx, &s.fy, &s.torque, &s.overlap,
        &s.initial_y, &s.gas_ux, &s.gas_uy, &s.porosity, &s.pressure, &s.z})
    put_vec(out, *v);
  put_vec(out, s.void_fraction);
  put_vec(out, s.bubble_edges);
  for (const std::vector<double>* v : depth_vectors(s)) put_vec(out, *v);
  put(out, s.gas_bottom);
}

void load_snapshot(BinarySource& in, Snapshot& s) {
  char tag[sizeof kSnapshotTag];
  in.stream().read(tag, sizeof tag);
  const bool earlier = in.stream() && std::memcmp(tag, kSnapshotTag, kTagVersion) == 0 &&
                       (tag[kTagVersion] == '2' || tag[kTagVersion] == '3');
  const bool version2 = earlier && tag[kTagVersion] == '2';
  if (!in.stream() || (!earlier && std::memcmp(tag, kSnapshotTag, sizeof tag) != 0))
    in.fail("not a snapshot's");
  for (double* v : {&s.time, &s.dt, &s.width, &s.height, &s.thickness, &s.jet_width,
                    &s.superficial_velocity, &s.jet_velocity, &s.dp, &s.max_overlap_ratio,
                    &s.kinetic_energy, &s.void_dx, &s.void_dy})
    *v = in.get<double>();
  s.step = in.get<std::int64_t>();
  s.top_wall = in.get<std::int32_t>() != 0;
  const auto inlet = in.get<std::int32_t>();
  if (inlet < 0 || inlet > static_cast<std::int32_t>(InletKind::None))
    in.fail("inconsistent (snapshot inlet)");
  s.inlet_kind = static_cast<InletKind>(inlet);
  for (int* v : {&s.jets, &s.contacts, &s.nx, &s.ny, &s.void_nx, &s.void_ny})
    *v = in.get<std::int32_t>();
  for (std::vector<double>* v :
       {&s.x, &s.y, &s.radius, &s.vx, &s.vy, &s.spin, &s.fx, &s.fy, &s.torque, &s.overlap,
        &s.initial_y, &s.gas_ux, &s.gas_uy, &s.porosity, &s.pressure, &s.z})
    in.get_vec(*v);
  in.get_vec(s.void_fraction);
  in.get_vec(s.bubble_edges);
  for (std::vector<double>* v : depth_vectors(s)) {
    if (version2)
      v->clear();
    else
      in.get_vec(*v);
  }
  s.gas_bottom = earlier ? 0.0 : in.get<double>();
}

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
  // In ids (the solver may keep its own order: DemSolver::renumbered), so that a particle
  // picked, tracked or written is the same one from frame to frame.
  const std::pair<const std::vector<double>*, std::vector<double>*> arrays[] = {
      {&p.x, &out.x},           {&p.y, &out.y},         {&p.z, &out.z},
      {&p.radius, &out.radius}, {&p.vx, &out.vx},       {&p.vy, &out.vy},
      {&p.w, &out.spin},        {&p.fx, &out.fx},       {&p.fy, &out.fy},
      {&p.torque, &out.torque}, {&p.vz, &out.vz},       {&p.fz, &out.fz},
      {&p.wx, &out.spin_x},     {&p.wy, &out.spin_y},   {&p.torque_x, &out.torque_x},
      {&p.torque_y, &out.torque_y}, {&dem.particle_overlap(), &out.overlap}};
  for (const auto& [from, to] : arrays) dem.to_ids(*from, *to);
  out.initial_y = sim.initial_heights();
  if (const GasSolver* g = sim.gas()) {
    out.inlet_kind = s.inlet.kind;
    out.jet_width = s.inlet.jet_width;
    out.jets = s.inlet.jets;
    out.superficial_velocity = g->superficial_velocity();
    out.jet_velocity = g->jet_velocity();
    out.nx = g->grid().nx;
    out.ny = g->grid().ny;
    out.gas_bottom = g->grid().bottom;
    const auto cells = static_cast<std::size_t>(g->grid().cells());
    out.gas_ux.resize(cells);
    out.gas_uy.resize(cells);
    for (std::size_t c = 0; c < cells; ++c) g->cell_velocity(static_cast<int>(c), out.gas_ux[c], out.gas_uy[c]);
    out.porosity = g->porosity();
    out.pressure = g->pressure();
  } else {
    out.inlet_kind = InletKind::None;
    out.nx = out.ny = 0;
    out.gas_bottom = 0.0;
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
