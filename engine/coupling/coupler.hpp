#pragma once
// The coupler between the particle state and the gas state, which know nothing of each other
// (model.md section 3's loop: particles -> porosity and F -> gas -> drag -> particles).
//
// Newton's third law (eq 21) holds exactly: each particle's drag is computed once per particle
// step, applied to the particle in the next step, and summed per cell (averaged over the particle
// steps of one gas step) as the force F the gas feels in that cell.
#include <cstdint>
#include <optional>
#include <vector>

#include "cfd/gas_grid.hpp"
#include "core/permute.hpp"
#include "coupling/block_sums.hpp"
#include "coupling/porosity.hpp"
#include "coupling/void_fraction_smoothing.hpp"
#include "dem/particles.hpp"

namespace fluidbed {

class GasSolver;

// What the coupler needs from a scene, built once from the settings
// (sim/model_params.hpp: coupler_params_for).
struct CouplerParams {
  double gas_density = 1.205;     // kg/m^3
  double gas_viscosity = 1.8e-5;  // Pa s
  // Model A (model.md 2.1): the particles feel drag and -V grad p; false: drag alone.
  bool pressure_gradient_force = true;
  // m: the void fraction smoothed over this length (coupling/void_fraction_smoothing.hpp);
  // 0: each cell's exact share (eq 22).
  double smoothing_length = 0.0;
  int threads = 1;  // inside a step; 0: one per core
};

// The coupler's part of a saved state (bit-exact restarts mid-run).
struct CouplingState {
  std::vector<double> eps;  // per cell
  std::vector<int> cell;    // per particle, frozen at the last gas step
  std::vector<double> beta, gas_ux, gas_uy, base_fx, base_fy;  // idem
  std::vector<double> drag_x, drag_y, sum_x, sum_y;  // per particle: last drag, summed drag
  int accumulated = 0;
  // The per-particle arrays reordered: the particle at from[s] moves to s (the particles'
  // renumbering, DemSolver::on_renumber; core/permute.hpp).
  void reorder(const std::vector<std::int32_t>& from) {
    gather_by(cell, from);
    for (auto* v : {&beta, &gas_ux, &gas_uy, &base_fx, &base_fy, &drag_x, &drag_y, &sum_x, &sum_y})
      gather_by(*v, from);
  }
};

class Coupler {
 public:
  Coupler(const GasGrid& grid, const CouplerParams& params, std::size_t particles);

  // Eq 22: the porosity of every cell from the particles' positions (the solid volume smoothed
  // first when CouplerParams::smoothing_length > 0). Throws SimulationFailure
  // naming the cell when a porosity leaves (0, 1].
  // `split`: each thread's particles (DemSolver::split(), so each particle's data stays on the
  // core that stepped it); empty: even blocks. Results are the same bits for any thread count.
  const std::vector<double>& compute_porosity(const Particles& p, double time,
                                              const std::vector<std::size_t>& split = {});
  const std::vector<double>& porosity() const { return s_.eps; }

  // Reads the gas field into per-cell arrays (velocity, pressure gradient, ln eps); call after
  // every gas step and whenever the gas state is replaced.
  void refresh_cells(const GasSolver& gas);

  // The fluid force on the particles (eqs 8-12, and -V grad p for model A) is linear in the
  // particle's velocity once its drag coefficient is fixed: f = beta (u_gas - v) + f_base.
  // At every gas step (and at the start) freeze_drag() takes, for every particle, its cell, the
  // gas velocity there, beta from the current slip, and f_base = -V grad p; it sets the force of
  // the next step, Particles::ext_fx/ext_fy. Between gas steps advance_drag() renews only the
  // slip, from the particle's current velocity. The gas needs porosity and F only when it
  // steps, so the drag law (logarithms and exponentials) is evaluated once per gas step, and
  // Newton's third law stays exact: the gas receives the mean of exactly the drags the
  // particles felt, each summed into the cell frozen with it. With one particle step per gas
  // step this is the paper's scheme: the drag from the gas and particle velocity at the end of
  // each step, held over the next.
  // `split`: each thread's particles (DemSolver::split(), so each particle's data stays on the
  // core that stepped it); empty: even blocks. Results are the same bits for any thread count.
  void freeze_drag(Particles& p, const std::vector<std::size_t>& split = {});
  // After every particle step: adds the drag of the step just taken to each particle's sum, then
  // (when `update`, i.e. no gas step follows) the force of the next step from the frozen
  // coefficients.
  void advance_drag(Particles& p, bool update, const std::vector<std::size_t>& split = {});
  // The same in two parts, for a caller that runs the particles' share inside its own parallel
  // region: count_step() once, then advance_drag_range() on every thread's particles.
  void count_step() { ++s_.accumulated; }
  void advance_drag_range(Particles& p, bool update, std::size_t begin, std::size_t end);

  // F per cell (N/m^3): each particle's summed drag in its frozen cell, averaged over the steps
  // since the last call; resets the sums. Also returns the total drag on the particles over
  // those steps (N, averaged) for the third-law check.
  void take_interaction_force(std::vector<double>& fx, std::vector<double>& fy, double& total_x,
                              double& total_y, const std::vector<std::size_t>& split = {});

  // What a gas step needs, in one pass of the threads over the particles: compute_porosity()
  // and take_interaction_force() (the same results).
  const std::vector<double>& exchange(const Particles& p, double time, std::vector<double>& fx,
                                      std::vector<double>& fy, double& total_x, double& total_y,
                                      const std::vector<std::size_t>& split = {});

  void save(CouplingState& out) const;
  void reorder(const std::vector<std::int32_t>& from) { s_.reorder(from); }
  // Throws InputError when the sizes do not fit this grid and particle count.
  void restore(const CouplingState& in, std::size_t particles);

  // N, per particle: the drag of the next step (the last one set).
  const std::vector<double>& drag_x() const { return s_.drag_x; }
  const std::vector<double>& drag_y() const { return s_.drag_y; }

 private:
  GasGrid grid_;
  double rho_f_, mu_f_;
  bool pressure_gradient_force_;
  int threads_ = 1;
  bool parallel_ = false;
  template <class F>
  void per_thread(std::size_t n, const std::vector<std::size_t>& split, F&& body);

  void freeze_range(Particles& p, int t, std::size_t begin, std::size_t end);
  struct FreezeScratch;
  void freeze_chunk(Particles& p, FreezeScratch& f, std::size_t begin, std::size_t end);
  void porosity_range(const Particles& p, int t, std::size_t begin, std::size_t end);
  void drag_sums_range(int t, std::size_t begin, std::size_t end);
  const std::vector<double>& finish_porosity(double time);
  void finish_interaction_force(std::vector<double>& fx, std::vector<double>& fy, double& total_x,
                                double& total_y);

  BlockCellSums sums_;  // per-cell sums over particles, block by block: solid volume
  // The porosity's and the drag's per-particle scratch is filled and used a chunk of this many
  // particles at a time (a multiple of kParticleBlock): sized for a chunk, not for every
  // particle, it no longer grows with the bed (84 bytes a particle, 7 % of the 240,000-sphere
  // bed's peak memory; docs/speed.md).
  static constexpr std::size_t kChunk = 256;
  std::vector<ShareGeometry> geometry_;  // per thread: scratch of the porosity, kChunk particles
  BlockCellSums drag_sums_;              // idem: drag
  std::vector<double> cell_ux_, cell_uy_, cell_gx_, cell_gy_, ln_eps_;  // per cell
  std::vector<double> solid_;
  std::optional<VoidFractionSmoother> smoother_;  // CouplerParams::smoothing_length > 0
  // What a restart needs (see CouplingState): per cell eps; per particle, frozen at the last gas
  // step, the cell of its centre, the gas velocity there (m/s), the drag coefficient (kg/s) and
  // the force that does not depend on the slip (N); the drag of the next step and the drags felt
  // since the last gas step (N); the steps counted since then.
  CouplingState s_;
  // Scratch of freeze_drag per thread, kChunk particles: slip (m/s), the cell's eps and ln eps.
  struct FreezeScratch {
    std::vector<double> slip_x, slip_y, slip, eps_at, ln_eps_at;
  };
  std::vector<FreezeScratch> freeze_scratch_;
  std::vector<double> cell_sum_x_, cell_sum_y_;  // N, per cell (take_interaction_force)
};

}  // namespace fluidbed
