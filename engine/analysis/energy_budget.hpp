#pragma once
// The particles' energy budget (issue: the ideal case): the mechanical energy of the state, split
// into its parts, and the work of everything else since a reference point, so that
//   (E_mech - E_mech at the reference) = gas work - dashpot losses - friction losses + residual.
// The residual is what the step-by-step sums do not account for: the time integration's error
// (and, with the incremental contact, the springs' drift from the geometry), zero for the exact
// motion. The springs' energy is taken from the contacts' displacement history, which is what the
// contact law's forces derive from.
#include <nlohmann/json.hpp>

#include "dem/dem_solver.hpp"

namespace fluidbed {

struct EnergyBudget {
  double kinetic_translation = 0.0;  // J, 1/2 m v^2
  double kinetic_rotation = 0.0;     // J, 1/2 I w^2
  double potential = 0.0;            // J, m g y
  double spring_normal = 0.0;        // J
  double spring_tangential = 0.0;    // J
  // Since the reference:
  double gas_work = 0.0;             // J, done by the gas on the particles
  double dashpot = 0.0;              // J, dissipated (>= 0)
  double friction = 0.0;             // J, dissipated (>= 0)
  double residual = 0.0;             // J, unaccounted for
  double mechanical() const {
    return kinetic_translation + kinetic_rotation + potential + spring_normal + spring_tangential;
  }
};

// The state's parts alone (the ledger terms zero).
EnergyBudget energy_state(const DemSolver& dem, double gravity);

// The budget now, measured from `reference` (an energy_state and ledger taken earlier).
EnergyBudget energy_budget(const DemSolver& dem, double gravity, const EnergyBudget& reference,
                           const EnergyLedger& reference_ledger);

// summary.json's "energy" block: the final parts, the terms since the start, the residual
// per simulated second and as a share of the largest term of the budget.
nlohmann::json energy_summary(const EnergyBudget& start, const EnergyBudget& end, double sim_time);

}  // namespace fluidbed
