#include "sim/model_params.hpp"

#include <cmath>

#include "dem/walls.hpp"

namespace fluidbed {

DemParams dem_params_for(const Settings& s) {
  DemParams d;
  d.contact.kn = s.contact.stiffness;
  d.contact.kt = s.contact.stiffness * s.contact.tangential_stiffness_ratio;
  d.contact.eta_n = s.contact.damping;
  d.contact.eta_t = s.contact.damping * s.contact.tangential_damping_ratio;
  d.contact.mu = s.contact.friction;
  d.wall_mu = s.contact.wall_friction;
  d.contact.mu_r = s.contact.rolling_friction;
  if (s.contact.law == ContactLaw::HertzMindlin)
    set_hertz(d.contact, s.contact.youngs_modulus.value_or(0.0),
              s.contact.poisson_ratio.value_or(0.0), s.contact.restitution.value_or(1.0));
  d.incremental = s.contact.displacement == Displacement::Incremental;
  d.integrator = s.time.integrator;
  d.dt = s.time.dt;
  d.gravity = s.physics.gravity;
  d.width = s.domain.width;
  d.height = s.domain.height;
  d.thickness = s.domain.thickness;
  const bool depth = slab_has_depth(s.domain, s.particles.diameter);
  d.walls = slab_walls(s.domain, depth);
  d.skin = s.contact.skin;
  const double bytes = static_cast<double>(s.particles.count) *
                       static_cast<double>(Particles::bytes_per_particle(depth));
  d.renumber_steps = s.contact.renumber_steps >= 0 ? s.contact.renumber_steps
                     : bytes >= kAutoRenumberBytes ? kAutoRenumberSteps
                                                   : 0;
  d.overlap_limit = s.diagnostics.overlap_limit;
  d.frozen = s.particles.frozen;
  d.threads = s.threads;
  return d;
}

GasGrid gas_grid_for(const Settings& s) {
  GasGrid g;
  g.nx = s.gas.cells_x;
  g.ny = s.gas.cells_y;
  g.width = s.domain.width;
  g.height = s.domain.height + s.inlet.plenum_height;
  g.bottom = -s.inlet.plenum_height;
  g.depth = s.domain.thickness;
  return g;
}

GasParams gas_params_for(const Settings& s) {
  GasParams p;
  p.density = s.gas.density;
  p.viscosity = s.gas.viscosity;
  p.gravity = s.physics.gravity;
  p.inlet = s.inlet.kind;
  p.superficial_velocity = s.inlet.superficial_velocity;
  p.jet_width = s.inlet.jet_width;
  p.jets = s.inlet.jets;
  p.tolerance = s.gas.tolerance;
  p.max_iterations = s.gas.max_iterations;
  p.preconditioner_refresh = s.gas.preconditioner_refresh;
  // The drag of the lower half of a bottom-row cell acts where the inflow velocity is fixed: it is
  // carried by the bottom wall's pressure, not moved onto the face above (which would bias the
  // bottom-row pressure gradient and the bed's pressure drop by 0.75 F dy / eps). The third-law
  // check counts force_on_gas + force_on_walls.
  p.wall_force_to_interior = false;
  // The distributor plate at the floor: the v faces of the row the floor lies on (validate.cpp
  // holds the floor to a cell boundary).
  if (s.inlet.distributor_resistance > 0.0) {
    const GasGrid g = gas_grid_for(s);
    p.plate_row = static_cast<int>(std::lround(s.inlet.plenum_height / g.dy()));
    p.plate_resistance = s.inlet.distributor_resistance;
  }
  return p;
}

CouplerParams coupler_params_for(const Settings& s) {
  CouplerParams c;
  c.gas_density = s.gas.density;
  c.gas_viscosity = s.gas.viscosity;
  c.pressure_gradient_force = s.coupling.pressure_gradient_force;
  if (s.coupling.void_fraction == VoidFraction::Smoothed)
    c.smoothing_length = s.coupling.void_fraction_length;
  c.threads = s.threads;
  return c;
}

}  // namespace fluidbed
