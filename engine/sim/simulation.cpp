#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/errors.hpp"
#include "core/hash.hpp"
#include "sim/model_params.hpp"
#include "sim/placement.hpp"
#include "sim/state_file.hpp"

namespace fluidbed {
namespace {

DemSolver make_dem(const Settings& s) {
  if (s.particles.placement != Placement::State && s.particles.placement != Placement::Packed)
    return DemSolver(dem_params_for(s), place_particles(s));
  // A saved configuration starts a new experiment: its contact history is kept, its clock
  // restarts, and the gas starts from rest with this scene's inflow.
  Settings from = s;
  if (s.particles.placement == Placement::Packed) {
    if (s.packed_state.empty())
      throw InputError("particles.placement = \"packed\": the packed bed was not prepared "
                       "(prepare_packed_bed, run/packed_bed.hpp, before building the simulation)");
    from.particles.state_file = s.packed_state;
  }
  DemState st = load_scene_state(from);
  st.time = 0.0;
  st.step = 0;
  // A bed packed without a lid may start a scene with one (domain.top_wall: walls are bottom,
  // left, right, then top): the top wall's history starts empty.
  const int walls =
      static_cast<int>(slab_walls(s.domain, slab_has_depth(s.domain, s.particles.diameter)).size());
  if (st.walls.walls == walls - 1 && s.domain.top_wall) st.walls.add_walls(walls);
  Particles p = st.particles;
  DemSolver dem(dem_params_for(s), std::move(p));
  dem.set_state(std::move(st));
  return dem;
}

}  // namespace

Simulation::Simulation(const Settings& s) : settings_(s), dem_(make_dem(s)) {
  dem_.to_ids(dem_.particles().y, initial_y_);
  if (!s.gas.enabled) return;
  const GasGrid grid = gas_grid_for(s);
  gas_ = std::make_unique<GasSolver>(grid, gas_params_for(s));
  coupler_ = std::make_unique<Coupler>(grid, coupler_params_for(s), particle_count());
  // The coupler's per-particle data follows the particles when the solver renumbers them (the
  // coupler is held by pointer: the hook stays valid when the simulation moves).
  Coupler* coupler = coupler_.get();
  dem_.on_renumber([coupler](const std::vector<std::int32_t>& from) { coupler->reorder(from); });
  Particles& p = dem_.particles();
  gas_->set_porosity(coupler_->compute_porosity(p, time()));
  coupler_->refresh_cells(*gas_);
  gas_speed_ = gas_->max_speed_per_cell();
  note_inlet_speed();
  coupler_->freeze_drag(p);
  // A fresh start has no carried acceleration beyond gravity: add the gas's share to it.
  if (s.particles.placement != Placement::State && s.particles.placement != Placement::Packed) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.ax[i] += p.ext_fx[i] * p.inv_mass[i];
      p.ay[i] += p.ext_fy[i] * p.inv_mass[i];
      if (p.has_depth()) p.az[i] += p.ext_fz[i] * p.inv_mass[i];
    }
  }
}

void Simulation::set_superficial_velocity(double u) {
  if (!gas_) return;
  gas_->set_superficial_velocity(u);
  note_inlet_speed();
}

void Simulation::step() {
  if (!gas_) {
    dem_.step();
    return;
  }
  // The gas every particle_steps_per_gas_step steps, or sooner while the gas is fast: a gas
  // step that would start above kGasCflTarget (the jet opening its cavity, a velocity raised
  // in the viewer) is taken now. With the paper's one step per gas step this never acts.
  const int since = since_gas_step_ + 1;
  const bool fast = gas_speed_ * (since + 1) * settings_.time.dt > kGasCflTarget;
  const bool gas_now = since >= settings_.coupling.particle_steps_per_gas_step || fast;
  // Inside the particle step's threads: the drag the particles felt in this step joins the
  // gas's sums, and, unless the gas steps now, the next step's force comes from the frozen
  // coefficients (after a gas step, from new ones).
  Particles& p = dem_.particles();
  coupler_->count_step();
  dem_.step([&](std::size_t b, std::size_t e) { coupler_->advance_drag_range(p, !gas_now, b, e); });
  since_gas_step_ = since;
  if (gas_now) {
    PhaseClock clock(dem_.phase_times());
    gas_step(clock);
    coupler_->freeze_drag(p, dem_.split());
    clock.lap(Phase::Coupling);
  }
}

void Simulation::gas_step(PhaseClock& clock) {
  const double dt = since_gas_step_ * settings_.time.dt;
  since_gas_step_ = 0;
  CouplingDiagnostics& d = coupling_diag_;
  const auto& eps = coupler_->exchange(dem_.particles(), time(), fx_, fy_, d.drag_total_x,
                                       d.drag_total_y, dem_.split());
  clock.lap(Phase::Coupling);
  d.gas = gas_->step(dt, eps, fx_, fy_);
  clock.lap(Phase::Gas);
  coupler_->refresh_cells(*gas_);
  gas_speed_ = gas_->max_speed_per_cell();
  ++d.gas_steps;
  gas_->force_on_gas(d.gas_force_x, d.gas_force_y);
  double wx = 0.0, wy = 0.0;
  gas_->force_on_walls(wx, wy);
  d.gas_force_x += wx;
  d.gas_force_y += wy;
  const double scale = std::hypot(d.drag_total_x, d.drag_total_y);
  const double miss = std::hypot(d.drag_total_x + d.gas_force_x, d.drag_total_y + d.gas_force_y);
  d.third_law_error = scale > 0.0 ? miss / scale : miss;
}

void Simulation::note_inlet_speed() {
  // The inlet faces take the inlet's velocity at the next gas step: count it before that step.
  const GasGrid& g = gas_->grid();
  gas_speed_ = std::max(gas_speed_, gas_->jet_velocity() / std::min(g.dx(), g.dy()));
}

std::uint64_t Simulation::state_hash() const {
  Fnv1a h;
  h.value(dem_.state_hash());
  if (gas_) h.value(gas_->state_hash());
  return h.digest();
}

void Simulation::save_state(const std::string& path) const {
  StateFile f;
  f.dem = dem_.exported_state();
  if (gas_) {
    f.has_gas = true;
    f.gas = gas_->state();
    f.since_gas_step = since_gas_step_;
    coupler_->save(f.coupling);
    if (dem_.renumbered()) f.coupling.reorder(dem_.places());  // in ids, as the particles
  }
  save_simulation_state(path, f);
}

void Simulation::load_state(const std::string& path) {
  StateFile f = load_simulation_state(path);
  if (f.has_gas != has_gas())
    throw InputError(path + (f.has_gas ? ": holds a gas state but the scene has no gas"
                                       : ": holds no gas state but the scene has gas"));
  dem_.set_state(std::move(f.dem));
  if (gas_) {
    gas_->set_state(f.gas);
    since_gas_step_ = f.since_gas_step;
    coupler_->restore(f.coupling, particle_count());
    if (dem_.renumbered()) coupler_->reorder(dem_.ids());  // from ids to the solver's order
    coupler_->refresh_cells(*gas_);
    gas_speed_ = gas_->max_speed_per_cell();
    // A state saved before its first gas step (the viewer's start) has still gas: the inlet's
    // jet counts, as it does for a fresh start (after a gas step it is in the faces already).
    note_inlet_speed();
  }
}

void Simulation::continue_from(const std::string& path) {
  load_state(path);
  DemState& st = dem_.state();
  st.time = 0.0;
  st.step = 0;
  if (gas_) {
    GasState g = gas_->state();
    g.time = 0.0;
    g.steps = 0;
    gas_->set_state(g);
    gas_->set_superficial_velocity(settings_.inlet.superficial_velocity);
    note_inlet_speed();
  }
  dem_.to_ids(dem_.particles().y, initial_y_);
}

}  // namespace fluidbed
