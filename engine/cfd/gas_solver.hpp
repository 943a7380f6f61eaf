#pragma once
// The gas: locally averaged equations of model.md section 3 (Xu & Yu 1997, eqs 18-20) on the
// staggered GasGrid, for an incompressible gas of constant density rho:
//
//   d(eps)/dt + div(eps u) = 0                                                          (18)
//   d(rho eps u)/dt + div(rho eps u u) = -eps grad p - F + div(eps tau) + rho eps g     (19)
//   tau = mu (grad u + grad u^T) - 2/3 mu (div u) I                                     (20)
//
// u is the interstitial velocity: u_x on the vertical faces, u_y on the horizontal faces; p and
// eps at the cell centres. F (N/m^3, per cell) is the force the gas exerts on the particles of a
// cell; the gas feels -F. g = -gravity along y.
//
// Method (the paper's): finite volumes; central differences for the pressure gradient and the
// divergence; first-order upwind convection; Crank-Nicolson in time for the momentum equations;
// SIMPLE for the pressure-velocity coupling. In one step:
//   - Crank-Nicolson: the convection and viscous terms are half at the old level (evaluated once,
//     at u^n, eps^n) and half at the new level (implicit in u^(n+1), with eps^(n+1)). The new
//     level's convecting mass fluxes and the cross-derivative viscous terms (the part of
//     div(eps tau) that involves the other velocity component) are taken at the velocity
//     extrapolated from the last two steps, 2 u^n - u^(n-1) (second order), so the momentum
//     matrix is built once per step (params.picard: update them from the latest iterate at every
//     SIMPLE iteration instead). The pressure force is the end-of-step one, -eps^(n+1)
//     grad p^(n+1); F and gravity are the step's. d(eps)/dt is (eps^(n+1) - eps^n) / dt.
//     Measured: second order in time with a fixed porosity (tests/unit/test_gas_time.cpp); with
//     a porosity that changes in time, first order (the continuity constraint at the end of the
//     step uses the backward difference of eps).
//   - SIMPLE iteration: momentum predictor with the current pressure (Gauss-Seidel sweeps on the
//     momentum system), continuity residual per cell, pressure-correction equation
//     sum_f c_f (p'_P - p'_nb) = -residual with c_f = (eps A)_f^2 / a_P (a_P of the first
//     iteration, kept for the step), solved by PCG (cfd/pressure_solver.hpp), then
//     u += d (p'_W - p'_E), p += pressure_relaxation p'. Stops when the predictor's residual
//     (sum over cells, relative to the reference flow) is below the tolerance; the correction of
//     that last iteration is applied too, so the state satisfies continuity to the PCG tolerance.
// At the paper's step (dt = 1.5e-5 s, CFL 0.06) this converges in 2 iterations.
//
// Boundaries: ghost cells outside. Left, right and bottom walls: no slip (normal velocity 0 on
// the wall face; the tangential ghost value is minus the inside value so the wall value is 0).
// Bottom inflow: a plug jet through a slot at the centre, a uniform distributor, or none; the
// inflowing gas has porosity 1 at the inlet face (face velocity = superficial velocity there).
// Top exit: zero normal gradient of velocity and porosity, pressure p = 0 at the exit face (the
// exit faces are solved, with half control volumes). Porosity and pressure correction: zero normal
// gradient at the walls. Wall pressure (for reporting and the cell pressure gradient) by linear
// extrapolation from the two nearest cells (second-order accurate).
#include <cstdint>
#include <string>
#include <vector>

#include "cfd/gas_grid.hpp"
#include "cfd/pressure_solver.hpp"
#include "scene/options.hpp"

namespace fluidbed {

struct GasParams {
  double density = 1.205;             // kg/m^3, air
  double viscosity = 1.8e-5;          // Pa s
  double gravity = 9.81;              // m/s^2, along -y
  InletKind inlet = InletKind::Jet;   // a jet slot, a uniform distributor or none (closed bottom)
  double superficial_velocity = 2.8;  // m/s, mean over the whole bottom
  double jet_width = 0.01;            // m, each slot (jet: U_jet = U W / (jets jet_width))
  int jets = 1;                       // slots centred at (k + 1/2) W / jets
  // SIMPLE stops when sum over cells |continuity residual| (m^3/s) is below tolerance times a
  // reference flow: the inflow U W dz, or when larger the porosity change sum |d eps/dt| dV, or
  // at least 1 mm/s over the bottom (a floor for a closed box at rest).
  double tolerance = 1e-6;
  int max_iterations = 50;  // SIMPLE iterations per step
  // Under-relaxation (1 = none). With the time term in the momentum diagonal none is needed,
  // at the paper's step as well as at a CFL number near 1 (steady channel flow).
  double velocity_relaxation = 1.0;
  double pressure_relaxation = 1.0;
  int momentum_sweeps = 2;  // Gauss-Seidel sweeps of the momentum equations per iteration
  // Convecting velocity of the new time level: false, extrapolated from the last two steps
  // (linearly implicit Crank-Nicolson, second order, one assembly per step); true, the latest
  // SIMPLE iterate (Picard: fully implicit; one assembly per SIMPLE iteration).
  bool picard = false;
  double pressure_tolerance = 1e-3;   // PCG: relative residual of the pressure-correction equation
  int pressure_max_iterations = 100;  // PCG iterations per solve
  // The PCG preconditioner (an exact factorization of an earlier matrix) is rebuilt when a face
  // coefficient has moved by more than this fraction since it was built.
  double preconditioner_refresh = 2e-3;
  // The banded factorization or the multigrid V-cycle: chosen by the grid's size (automatic;
  // PressureSolver says where), not a scene key; tests and benchmarks may name one.
  PressureMethod pressure_method = PressureMethod::automatic;
  // Where the half of a wall cell's F that falls on a fixed-velocity face (side walls, bottom)
  // goes. true: to the cell's other (solved) face, so the gas receives exactly sum F_c dV; but in
  // a uniform bed the face above the bottom row then carries 1.5 F, so grad p in the bottom row
  // is 1.5 F / eps and the bed pressure drop is 0.75 F dy / eps too high (~6 % of the paper's
  // 3550 Pa). false: to the wall (the usual staggered discretization): unbiased pressure, and
  // force_on_gas() + force_on_walls() = -sum F_c dV. See tests/unit/test_gas_balance.cpp.
  bool wall_force_to_interior = true;
  // A distributor plate on the row of bottom faces plate_row (the particles' floor over a
  // plenum): the pressure drops across it by plate_resistance times the superficial velocity
  // through it (Pa s/m; 0: no plate).
  double plate_resistance = 0.0;
  int plate_row = 0;
};

// m/s: the gas speed through the slots of a jet inlet, `jets` slots of jet_width (m) each in a
// bottom of `width` (m) that carry the superficial velocity u (m/s, the mean over the whole
// bottom): u width / (jets jet_width). The one place this is computed (the gas solver's inlet,
// the scene checks, the OpenFOAM case).
inline double jet_slot_velocity(double u, double width, int jets, double jet_width) {
  return u * width / (jets * jet_width);
}

// Throws InputError naming the field when the parameters or the grid are impossible.
void validate_gas(const GasGrid& grid, const GasParams& params);

struct GasStepReport {
  int simple_iterations = 0;
  double mass_residual = 0.0;  // of the last SIMPLE iteration, before its correction (relative)
  int pressure_iterations_total = 0;  // PCG iterations over all SIMPLE iterations of the step
  double pressure_residual = 0.0;     // largest final relative residual of a pressure solve
  bool converged = false;             // mass_residual < tolerance
  double max_cfl = 0.0;               // max(|u|, |v|) dt / min(dx, dy) over the faces
  bool preconditioner_rebuilt = false;
  int substeps = 1;  // > 1: the flow outran the step, which was taken again in this many parts
};

// Everything a bit-exact restart needs.
struct GasState {
  std::vector<double> u;    // m/s, x-velocity on vertical faces, j * (nx + 1) + i
  std::vector<double> v;    // m/s, y-velocity on horizontal faces, j * nx + i (row 0: inlet)
  std::vector<double> p;    // Pa, cell centres, relative to the exit pressure
  std::vector<double> eps;  // porosity at the end of the last step (the next step's old level)
  // The pressure-correction coefficients the preconditioner was factorized from.
  std::vector<double> preconditioner_u, preconditioner_v;
  // The step before (u^(n-1), v^(n-1)) and its length: the new level convects with the velocity
  // extrapolated from the last two steps.
  std::vector<double> u_previous, v_previous;
  double dt_previous = 0.0;           // s (0: no history yet)
  double superficial_velocity = 0.0;  // m/s, inlet setting for the next step
  double time = 0.0;                  // s
  std::int64_t steps = 0;
};

class GasSolver {
 public:
  // Gas at rest, hydrostatic pressure, eps = 1. Throws InputError for impossible parameters.
  GasSolver(const GasGrid& grid, const GasParams& params);

  // Advances by dt (s). eps: cell porosity at the end of the step (nx * ny values in (0, 1]);
  // fx, fy: F per cell (N/m^3). The previous porosity gives d(eps)/dt. Throws SimulationFailure
  // (naming the cell and the time) when the CFL number exceeds 1, a value goes NaN, or SIMPLE
  // ends with a mass residual above 1000 x tolerance; below that, converged = false.
  // A step that starts at a CFL number in (kSplitFromCfl, 1] but ends above 1 (the flow sped up
  // within it: a jet opening its cavity, a raised inlet) is taken again from its start as up to
  // kMaxSubsteps equal sub-steps of CFL about kSubstepCfl, with the same F and the porosity moving
  // linearly to eps; it fails only if a sub-step is still above 1. The report sums the sub-steps,
  // and the solver's own step count (GasState::steps, "gas step N" in messages) counts each.
  GasStepReport step(double dt, const std::vector<double>& eps, const std::vector<double>& fx,
                     const std::vector<double>& fy);

  static constexpr double kSplitFromCfl = 0.5;
  static constexpr double kSubstepCfl = 0.8;
  static constexpr int kMaxSubsteps = 4;

  void set_superficial_velocity(double u);  // m/s, from the next step on
  // Porosity without a time derivative (the start from a packed bed).
  void set_porosity(const std::vector<double>& eps);

  const GasGrid& grid() const { return grid_; }
  const GasParams& params() const { return params_; }
  double time() const { return s_.time; }
  double superficial_velocity() const { return s_.superficial_velocity; }
  // 1/s: the largest face speed over the smallest cell side, so that dt times it is the CFL number
  // a gas step of dt would start from.
  double max_speed_per_cell() const {
    int face = 0;
    bool is_u = true;
    return max_cfl(1.0, face, is_u);
  }
  double jet_velocity() const;  // m/s, U W / (jets jet_width) for a jet inlet, U otherwise

  const std::vector<double>& u() const { return s_.u; }         // m/s, (nx + 1) * ny
  const std::vector<double>& v() const { return s_.v; }         // m/s, nx * (ny + 1)
  const std::vector<double>& pressure() const { return s_.p; }  // Pa
  const std::vector<double>& porosity() const { return s_.eps; }

  // Interstitial velocity at the centre of cell c (average of its faces), m/s.
  void cell_velocity(int c, double& ux, double& uy) const {
    const int i = c % grid_.nx, j = c / grid_.nx;
    const int f = j * (grid_.nx + 1) + i;
    ux = 0.5 * (s_.u[f] + s_.u[f + 1]);
    uy = 0.5 * (s_.v[c] + s_.v[c + grid_.nx]);
  }
  // grad p at the centre of cell c (Pa/m): difference of the face pressures (the mean of the two
  // cells, the extrapolated wall pressure, p = 0 at the exit) over the cell size; in the
  // interior this is the central difference (p_E - p_W) / 2 dx.
  void pressure_gradient(int c, double& gx, double& gy) const;
  // Pressure on the bottom wall below column i (linear extrapolation of the two lowest cells).
  double bottom_pressure(int i) const;
  // Bed pressure drop (Pa) on the symmetry line: bottom wall pressure of the middle column (the
  // mean of the two middle columns when nx is even) minus the exit pressure (0).
  double pressure_drop() const;

  // Volume flows of the last state, m^3/s: in through the bottom, out through the top.
  double inflow() const;
  double outflow() const;
  // The total of -F as applied to the gas's momentum equations in the last step (N): equals
  // -sum F_c dV when wall_force_to_interior; otherwise the rest is in force_on_walls().
  void force_on_gas(double& fx, double& fy) const;
  void force_on_walls(double& fx, double& fy) const;

  const GasState& state() const { return s_; }
  // Replaces the state (a loaded file); array sizes must match the grid (InputError otherwise).
  void set_state(const GasState& s);
  std::uint64_t state_hash() const;

 private:
  struct Coefficients {  // one momentum component: u_P = (sum a_nb u_nb + b) / a_P
    std::vector<double> ap, inv_ap, ae, aw, an, as;
    std::vector<double> b0;    // N, b without the pressure force and the relaxation term
    std::vector<double> b;     // N, b of the current SIMPLE iteration
    std::vector<double> area;  // m^2, eps times the face area: pressure force = area (p_W - p_E)
    std::vector<double> d;     // m^2 s/kg, velocity correction per pressure-correction difference
  };

  // One step of dt without the checks or the clock (step() adds them).
  GasStepReport solve(double dt, const std::vector<double>& eps, const std::vector<double>& fx,
                      const std::vector<double>& fy);
  void check(const GasStepReport& rep, double dt) const;  // CFL above 1, SIMPLE far off: fail
  void commit(double dt);                                 // the step becomes the history
  void prepare_step(double dt, const std::vector<double>& eps, const std::vector<double>& fx,
                    const std::vector<double>& fy);
  void face_porosities(const std::vector<double>& eps, std::vector<double>& eu,
                       std::vector<double>& ev, std::vector<double>& ek) const;
  void set_inlet(std::vector<double>& v, double superficial) const;
  void mass_fluxes(const double* u, const double* v, const double* eu, const double* ev);
  template <bool System>
  void assemble_u(const double* u, const double* v, const double* eps, const double* ek,
                  double* out);
  template <bool System>
  void assemble_v(const double* u, const double* v, const double* eps, const double* ek,
                  double* out);
  void momentum_system(bool first_iteration);
  void iteration_source();
  void sweep_u(int sweeps);
  void sweep_v(int sweeps);
  double continuity_residual();  // fills res_ (= minus the residual), returns sum |residual|
  void correct(bool first_iteration, GasStepReport& rep);
  [[noreturn]] void report_non_finite(const char* what) const;
  double max_cfl(double dt, int& face, bool& is_u) const;
  [[noreturn]] void fail(const std::string& what) const;

  GasGrid grid_;
  GasParams params_;
  int nx_, ny_;
  double dx_, dy_, dz_, vol_;
  std::vector<double> inlet_profile_;  // bottom face velocity per unit superficial velocity

  GasState s_;
  PressureSolver pressure_;

  // Per step: old level, porosities at faces and corners (old and new), forces on faces.
  double dt_ = 0.0, q_ref_ = 0.0;
  std::vector<double> u_old_, v_old_, eps_old_;
  std::vector<double> eu_new_, ev_new_, ek_new_, eu_old_, ev_old_, ek_old_;
  bool faces_current_ = false;   // eu_new_, ev_new_, ek_new_ belong to s_.eps
  std::vector<double> fu_, fv_;  // N, share of F on each face (what the gas exerts on particles)
  double wall_fx_ = 0.0, wall_fy_ = 0.0;  // N, the share left on the walls
  std::vector<double> old_u_, old_v_;     // N, the old-level spatial operator (Crank-Nicolson half)
  std::vector<double> u_ext_, v_ext_;     // m/s, 2 u^n - u^(n-1): new-level convecting velocity
  std::vector<double> m_u_, m_v_;         // kg/s, mass fluxes through the faces
  Coefficients cu_, cv_;
  std::vector<double> res_, pcorr_;  // per cell: continuity residual, pressure correction
  int cfl_face_ = 0;                 // where the last solve's largest CFL number is
  bool cfl_face_is_u_ = true;
};

}  // namespace fluidbed
