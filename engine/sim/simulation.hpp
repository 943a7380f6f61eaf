#pragma once
// A scene's model put together: the particle solver, the gas solver and the coupler between
// them, each knowing nothing of the others. Owns the state; one call advances it by one
// particle time step (and the gas every coupling.particle_steps_per_gas_step steps).
#include <cstdint>
#include <memory>
#include <string>

#include "cfd/gas_solver.hpp"
#include "coupling/coupler.hpp"
#include "dem/dem_solver.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

// What the last gas step reported, and the coupling checks.
struct CouplingDiagnostics {
  GasStepReport gas;
  int gas_steps = 0;
  // |sum of drag on the particles + total force applied to the gas| over the last gas step,
  // relative to the sum of |drag| (Newton's third law, eq 21; round-off only).
  double third_law_error = 0.0;
  double drag_total_x = 0.0, drag_total_y = 0.0;  // N, on the particles
  // N, applied to the gas: its momentum equations plus the share its fixed-velocity boundary
  // faces carry into the wall pressure.
  double gas_force_x = 0.0, gas_force_y = 0.0;
};

class Simulation {
 public:
  // A sub-stepped gas (coupling.particle_steps_per_gas_step > 1) steps early rather than let its
  // CFL number exceed this (the gas solver refuses a step above 1).
  static constexpr double kGasCflTarget = 0.8;

  explicit Simulation(const Settings& s);

  void step();

  // The scene it was built from. Its inlet.superficial_velocity stays the scene's: the velocity
  // the gas takes is the gas solver's (gas()->superficial_velocity(); set_superficial_velocity).
  const Settings& settings() const { return settings_; }
  const DemSolver& dem() const { return dem_; }
  DemSolver& dem() { return dem_; }
  double time() const { return dem_.time(); }
  std::int64_t steps() const { return dem_.state().step; }
  std::size_t particle_count() const { return dem_.particles().size(); }

  bool has_gas() const { return gas_ != nullptr; }
  const GasSolver* gas() const { return gas_.get(); }
  const Coupler* coupler() const { return coupler_.get(); }
  const CouplingDiagnostics& coupling_diagnostics() const { return coupling_diag_; }
  // A run resumed from a checkpoint (run/checkpoint.hpp): the last gas step's report as it was,
  // for the rows recorded before the next gas step.
  void set_coupling_diagnostics(const CouplingDiagnostics& d) { coupling_diag_ = d; }
  // Particle steps since the last gas step (0 right after one; with gas only).
  int steps_since_gas_step() const { return since_gas_step_; }
  // Pa, bottom to top on the symmetry line (0 without gas).
  double pressure_drop() const { return gas_ ? gas_->pressure_drop() : 0.0; }
  // The superficial gas velocity from the next gas step on (m/s). Its one owner is the gas
  // solver (its state: saved, restored and hashed with it); without gas there is nothing to set.
  void set_superficial_velocity(double u);

  // Each particle's height when this simulation started (for colouring by initial height band).
  const std::vector<double>& initial_heights() const { return initial_y_; }

  std::uint64_t state_hash() const;
  void save_state(const std::string& path) const;
  // Bit-exact restart: replaces the whole state (particles, gas, coupling), time included.
  void load_state(const std::string& path);
  // A new run from where another ended (the sweep's decreasing branch): the whole state of the
  // file, with the clock set back to zero and this scene's inlet velocity.
  void continue_from(const std::string& path);

 private:
  void gas_step(PhaseClock& clock);
  void note_inlet_speed();

  Settings settings_;
  DemSolver dem_;
  std::unique_ptr<GasSolver> gas_;
  std::unique_ptr<Coupler> coupler_;
  int since_gas_step_ = 0;
  double gas_speed_ = 0.0;  // 1/s, GasSolver::max_speed_per_cell after the last gas step
  std::vector<double> initial_y_;
  std::vector<double> fx_, fy_;  // scratch: F per cell
  CouplingDiagnostics coupling_diag_;
};


}  // namespace fluidbed
