#include "analysis/energy_budget.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed {

EnergyBudget energy_state(const DemSolver& dem, double gravity) {
  EnergyBudget e;
  const Particles& p = dem.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    e.kinetic_translation += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i]);
    e.kinetic_rotation += 0.5 * p.w[i] * p.w[i] / p.inv_inertia[i];
    e.potential += p.mass[i] * gravity * p.y[i];
  }
  if (p.has_depth())  // a thick slab: motion across it and spin about x and y
    for (std::size_t i = 0; i < p.size(); ++i) {
      e.kinetic_translation += 0.5 * p.mass[i] * p.vz[i] * p.vz[i];
      e.kinetic_rotation += 0.5 * (p.wx[i] * p.wx[i] + p.wy[i] * p.wy[i]) / p.inv_inertia[i];
    }
  const SpringEnergy s = dem.spring_energy();
  e.spring_normal = s.normal;
  e.spring_tangential = s.tangential;
  return e;
}

EnergyBudget energy_budget(const DemSolver& dem, double gravity, const EnergyBudget& reference,
                           const EnergyLedger& reference_ledger) {
  EnergyBudget e = energy_state(dem, gravity);
  const EnergyLedger& l = dem.energy_ledger();
  e.gas_work = l.gas_work - reference_ledger.gas_work;
  e.dashpot = l.dashpot - reference_ledger.dashpot;
  e.friction = l.friction - reference_ledger.friction;
  e.residual = (e.mechanical() - reference.mechanical()) - e.gas_work + e.dashpot + e.friction;
  return e;
}

nlohmann::json energy_summary(const EnergyBudget& start, const EnergyBudget& end, double sim_time) {
  nlohmann::json j;
  j["kinetic_translation_j"] = end.kinetic_translation;
  j["kinetic_rotation_j"] = end.kinetic_rotation;
  j["potential_j"] = end.potential;
  j["spring_normal_j"] = end.spring_normal;
  j["spring_tangential_j"] = end.spring_tangential;
  j["mechanical_change_j"] = end.mechanical() - start.mechanical();
  j["gas_work_j"] = end.gas_work;
  j["dashpot_dissipation_j"] = end.dashpot;
  j["friction_dissipation_j"] = end.friction;
  j["residual_j"] = end.residual;
  j["residual_per_s_w"] = sim_time > 0.0 ? end.residual / sim_time : 0.0;
  // Against the largest flow of the budget (the energy that went through it).
  const double scale = std::max({std::fabs(end.gas_work), end.dashpot + end.friction,
                                 std::fabs(end.mechanical() - start.mechanical()),
                                 start.kinetic_translation + start.kinetic_rotation});
  j["residual_share"] = scale > 0.0 ? end.residual / scale : 0.0;
  return j;
}

}  // namespace fluidbed
