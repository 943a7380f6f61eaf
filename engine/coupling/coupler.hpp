#pragma once
// The coupler between the particle state and the gas state, which know nothing of each other
// (model.md section 3's loop: particles -> porosity and F -> gas -> drag -> particles).
//
// Newton's third law (eq 21) holds exactly: each particle's drag is computed once per particle
// step, applied to the particle in the next step, and summed per cell (averaged over the particle
// steps of one gas step) as the force F the gas feels in that cell.
#include <vector>

#include "cfd/gas_grid.hpp"
#include "coupling/block_sums.hpp"
#include "coupling/porosity.hpp"
#include "dem/particles.hpp"

namespace fluidbed {

class GasSolver;

// What the coupler needs from a scene, built once from the settings
// (sim/model_params.hpp: coupler_params_for).
struct CouplerParams {
  double gas_density = 1.205;      // kg/m^3
  double gas_viscosity = 1.8e-5;   // Pa s
  // Model A (model.md 2.1): the particles feel drag and -V grad p; false: drag alone.
  bool pressure_gradient_force = true;
  int threads = 1;                 // inside a step; 0: one per core
};

// The coupler's part of a saved state (bit-exact restarts mid-run).
struct CouplingState {
  std::vector<double> eps, drag_x, drag_y, sum_fx, sum_fy;
  std::vector<int> cell;
  int accumulated = 0;
};

class Coupler {
 public:
  Coupler(const GasGrid& grid, const CouplerParams& params, std::size_t particles);

  // Eq 22: the porosity of every cell from the particles' positions. Throws SimulationFailure
  // naming the cell when a porosity leaves (0, 1].
  // `split`: each thread's particles (DemSolver::split(), so each particle's data stays on the
  // core that stepped it); empty: even blocks. Results are the same bits for any thread count.
  const std::vector<double>& compute_porosity(const Particles& p, double time,
                                              const std::vector<std::size_t>& split = {});
  const std::vector<double>& porosity() const { return eps_; }

  // Reads the gas field into per-cell arrays (velocity, pressure gradient, ln eps); call after
  // every gas step and whenever the gas state is replaced.
  void refresh_cells(const GasSolver& gas);
  // Eqs 8-12 (and -V grad p for model A) on every particle from the gas field read by the last
  // refresh_cells and the particles' current velocities, written to Particles::ext_fx/ext_fy.
  void compute_fluid_forces(Particles& p, const std::vector<std::size_t>& split = {});
  // The same for particles [begin, end) only (a thread's share inside a parallel region).
  void compute_fluid_forces(Particles& p, std::size_t begin, std::size_t end);

  // Adds the drag of the step just taken to the per-cell sums (call after each particle step).
  void accumulate_drag(const Particles& p, const std::vector<std::size_t>& split = {});
  // F per cell (N/m^3), averaged over the accumulated steps; resets the sums. Also returns the
  // total drag on the particles over those steps (N, averaged) for the third-law check.
  void take_interaction_force(std::vector<double>& fx, std::vector<double>& fy, double& total_x,
                              double& total_y);

  void save(CouplingState& out) const;
  // Throws InputError when the sizes do not fit this grid and particle count.
  void restore(const CouplingState& in, std::size_t particles);

  const std::vector<double>& drag_x() const { return drag_x_; }
  const std::vector<double>& drag_y() const { return drag_y_; }

 private:
  GasGrid grid_;
  double rho_f_, mu_f_;
  bool pressure_gradient_force_;
  int threads_ = 1;
  bool parallel_ = false;
  template <class F>
  void per_thread(std::size_t n, const std::vector<std::size_t>& split, F&& body);
  template <class F>
  void sum_blocks(int t, std::size_t b, std::size_t e, F&& add_particle);

  BlockCellSums sums_;  // per-cell sums over particles, block by block
  std::vector<double> cell_ux_, cell_uy_, cell_gx_, cell_gy_, ln_eps_;  // per cell
  std::vector<double> solid_, eps_;
  std::vector<double> drag_x_, drag_y_;  // N, per particle, from the last compute_fluid_forces
  std::vector<int> cell_;                // cell of each particle's centre at that time
  // Scratch per particle for compute_fluid_forces: slip (m/s), the cell's eps and ln eps, beta.
  std::vector<double> slip_x_, slip_y_, slip_, eps_at_, ln_eps_at_, beta_;
  std::vector<double> sum_fx_, sum_fy_;  // N, per cell, summed over steps
  int accumulated_ = 0;
};

}  // namespace fluidbed
