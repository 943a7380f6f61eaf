#include "sim/checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <numbers>
#include <sstream>

#include "cfd/gas_solver.hpp"
#include "core/errors.hpp"
#include "core/text_format.hpp"
#include "dem/contact_law.hpp"
#include "dem/walls.hpp"
#include "sim/model_params.hpp"

namespace fluidbed {
namespace {

std::string fmt(const char* f, double v) { return format_number(f, v); }

// How `check` found the contact duration.
std::string contact_duration_form(const Settings& s) {
  return s.contact.law == ContactLaw::HertzMindlin
             ? "Hertz at an impact of " + fmt("%g m/s", kHertzImpactSpeed)
             : "pi sqrt(m / kappa)";
}

}  // namespace

// Measured by `fluidbed study integrators --out DIR` (app/studies/accuracy.cpp; DIR/summary.md
// and DIR/study.csv), full size, steps of 0.1 to 13.5 x t_c / 9 with t_c the sphere-wall contact
// duration: every integrator (predictor-corrector, velocity Verlet, symplectic Euler) is stable
// up to 2 x t_c / 9 = 0.222 t_c and unstable from 2.5 x t_c / 9 = 0.278 t_c (the undamped
// packing of 2400 spheres at rest gains energy: its highest contact frequency, several contacts
// on a sphere, passes omega dt = 2 there); 13.5 x t_c / 9 = 1.5 t_c fails for all three. The drop
// test's error after 10 bounces stays under 5 % up to 1.75 x t_c / 9 (at most 4.7 %, at 1.5x)
// and is 10-24 % at 2x. `--size tiny` agrees: stable at 2x, unstable at 3x.
StepLimits measured_step_limits(Integrator integrator) {
  switch (integrator) {
    case Integrator::Newmark:
    case Integrator::VelocityVerlet:
    case Integrator::SymplecticEuler:
      break;  // the same limits for all three, as measured
  }
  return {1.75 / 9.0, 2.0 / 9.0, 2.5 / 9.0};
}

double wen_yu_umf(double d, double rho_p, double rho_g, double mu, double g) {
  const double ar = d * d * d * rho_g * (rho_p - rho_g) * g / (mu * mu);
  if (!(ar > 0.0)) return 0.0;  // particles no heavier than the gas, or no gravity
  const double re = std::sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7;
  return re * mu / (rho_g * d);
}

SceneCheck check_scene(const Settings& s) {
  SceneCheck c;
  SceneFigures& f = c.figures;
  const auto& p = s.particles;
  const double d = p.diameter, k = s.contact.stiffness, eta = s.contact.damping;
  f.particle_mass = p.density * std::numbers::pi * d * d * d / 6.0;
  const bool hertz = s.contact.law == ContactLaw::HertzMindlin;
  if (hertz) {  // Hertz's duration hangs on the impact speed: taken at kHertzImpactSpeed
    const ContactParams law = dem_params_for(s).contact;  // the run's own material constants
    f.contact_duration_wall =
        hertz_contact_duration(law.hertz_kn, 0.5 * d, f.particle_mass, kHertzImpactSpeed);
    f.contact_duration_pair =
        hertz_contact_duration(law.hertz_kn, 0.25 * d, 0.5 * f.particle_mass, kHertzImpactSpeed);
    f.restitution_wall = f.restitution_pair = s.contact.restitution.value_or(1.0);
  } else {
    f.contact_duration_wall = contact_duration(k, f.particle_mass);
    f.contact_duration_pair = contact_duration(k, 0.5 * f.particle_mass);
    f.restitution_wall = restitution_from_damping(k, eta, f.particle_mass);
    f.restitution_pair = restitution_from_damping(k, eta, 0.5 * f.particle_mass);
  }
  f.dt_over_tc_wall = s.time.dt / f.contact_duration_wall;
  f.dt_over_tc_pair = s.time.dt / f.contact_duration_pair;
  const std::string duration_form = contact_duration_form(s);
  f.weight_per_area =
      p.count * f.particle_mass * s.physics.gravity / (s.domain.width * s.domain.thickness);

  const StepLimits lim = measured_step_limits(s.time.integrator);
  const std::string integrator = option_string(s.time.integrator);
  const double tc = f.contact_duration_wall;
  const std::string step = "time.dt = " + fmt("%.4g s", s.time.dt) + " is " +
                           fmt("%.3g", f.dt_over_tc_wall) +
                           " x the contact duration t_c = " + fmt("%.4g s", tc) + " (" +
                           duration_form + ", sphere on a wall)";
  const auto at = [&](double share) {
    return fmt("%.3g t_c", share) + " = " + fmt("%.3g s", share * tc);
  };
  if (f.dt_over_tc_wall >= lim.unstable) {
    c.refusals.push_back(step + ": beyond the stability limit of " + integrator +
                         " (`fluidbed study integrators` measured it unstable from " +
                         at(lim.unstable) + ", the largest stable step " + at(lim.largest_stable) +
                         ")");
  } else if (f.dt_over_tc_wall > lim.largest_stable) {
    c.warnings.push_back(step + ": past the largest step measured stable, " +
                         at(lim.largest_stable) + " (unstable from " + at(lim.unstable) +
                         ", `fluidbed study integrators`)");
  } else if (f.dt_over_tc_wall > lim.accurate) {
    c.warnings.push_back(step + ": past " + at(lim.accurate) +
                         ", beyond which the drop test's error "
                         "after 10 bounces passes 5 % (`fluidbed study integrators`)");
  }
  if (f.restitution_wall == 0.0)
    c.warnings.push_back("contact.damping = " + fmt("%g kg/s", eta) +
                         " overdamps a sphere on a wall (restitution 0): contacts do not rebound");

  if (!s.gas.enabled) return c;
  f.gas = true;
  const auto& in = s.inlet;
  const auto& g = s.gas;
  switch (in.kind) {
    case InletKind::Jet:
      f.jet_velocity =
          jet_slot_velocity(in.superficial_velocity, s.domain.width, in.jets, in.jet_width);
      break;
    case InletKind::Uniform:
      f.jet_velocity = in.superficial_velocity;
      break;
    case InletKind::None:
      f.jet_velocity = 0.0;
      break;
  }
  f.archimedes = d * d * d * g.density * (p.density - g.density) * s.physics.gravity /
                 (g.viscosity * g.viscosity);
  f.umf_wen_yu = wen_yu_umf(d, p.density, g.density, g.viscosity, s.physics.gravity);
  f.cell_dx = s.domain.width / g.cells_x;
  f.cell_dy = (s.domain.height + s.inlet.plenum_height) / g.cells_y;
  const double dx = f.cell_dx, dy = f.cell_dy;
  f.cell_dx_over_d = dx / d;
  f.cell_dy_over_d = dy / d;
  f.gas_dt = s.time.dt * s.coupling.particle_steps_per_gas_step;
  f.gas_cfl_at_jet = f.jet_velocity * f.gas_dt / std::min(dx, dy);
  // The run stops when a gas step's CFL number passes 1 (run/run_loop.hpp); a gas step that would
  // pass 0.8 is taken early, but never sooner than every particle step.
  const double cfl_one_step = f.jet_velocity * s.time.dt / std::min(dx, dy);
  if (cfl_one_step > 1.0)
    c.warnings.push_back("the gas CFL number at the jet velocity " +
                         fmt("%.3g m/s", f.jet_velocity) + " is " + fmt("%.3g", cfl_one_step) +
                         " even with the gas solved every particle step (time.dt = " +
                         fmt("%.3g s", s.time.dt) + "): the run stops where it passes 1");
  return c;
}

std::string describe_check(const Settings& s, const SceneCheck& c) {
  const SceneFigures& f = c.figures;
  const StepLimits lim = measured_step_limits(s.time.integrator);
  std::ostringstream o;
  auto line = [&](const std::string& name, const std::string& value) {
    o << "  " << name << std::string(name.size() < 34 ? 34 - name.size() : 1, ' ') << value << "\n";
  };
  o << s.scene.name << ": " << s.particles.count << " particles of "
    << fmt("%g mm", 1e3 * s.particles.diameter) << ", " << option_string(s.time.integrator)
    << ", time.dt = " << fmt("%.4g s", s.time.dt) << "\n";
  line("particle mass m", fmt("%.4g kg", f.particle_mass) + " (rho pi d^3 / 6)");
  line("contact duration, wall (m)",
       fmt("%.4g s", f.contact_duration_wall) + " (" + contact_duration_form(s) + ")");
  line("contact duration, pair (m / 2)", fmt("%.4g s", f.contact_duration_pair));
  line("dt / t_c, wall", fmt("%.3g", f.dt_over_tc_wall) +
                             " (t_c / dt = " + fmt("%.3g", 1.0 / f.dt_over_tc_wall) + ")");
  line("dt / t_c, pair", fmt("%.3g", f.dt_over_tc_pair));
  line("largest stable dt (measured)",
       fmt("%.3g t_c", lim.largest_stable) + " = " +
           fmt("%.3g s", lim.largest_stable * f.contact_duration_wall));
  line("unstable dt (measured)", fmt("%.3g t_c", lim.unstable) + " = " +
                                     fmt("%.3g s", lim.unstable * f.contact_duration_wall));
  line("accurate dt (drop error < 5 %)", fmt("%.3g t_c", lim.accurate) + " = " +
                                             fmt("%.3g s", lim.accurate * f.contact_duration_wall));
  line("restitution, wall",
       fmt("%.4g", f.restitution_wall) + (s.contact.law == ContactLaw::HertzMindlin
                                               ? " (contact.restitution)"
                                               : " (from contact.damping)"));
  line("restitution, pair", fmt("%.4g", f.restitution_pair));
  line("bed weight per area W/A",
       fmt("%.4g Pa", f.weight_per_area) + " (N m g / (width thickness))");
  const double layers = s.domain.thickness / s.particles.diameter;
  line("slab depth", fmt("%.3g d", layers) +
                         (slab_has_depth(s.domain, s.particles.diameter)
                              ? ": particles move in 3D, the front and back walls are contacts"
                              : ": one layer, centres on the mid-plane (the paper's bed)"));
  if (f.gas) {
    line("jet velocity",
         fmt("%.4g m/s", f.jet_velocity) +
             (s.inlet.kind == InletKind::Jet ? " (U width / (jets jet_width))" : ""));
    line("U_mf, Wen-Yu", fmt("%.3g m/s", f.umf_wen_yu) +
                             " (Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7, Ar = " +
                             fmt("%.3g", f.archimedes) + "; eps_mf about 0.4 implied)");
    if (s.inlet.kind != InletKind::None && f.umf_wen_yu > 0.0)
      line("U / U_mf", fmt("%.3g", s.inlet.superficial_velocity / f.umf_wen_yu));
    line("gas cell / d",
         fmt("%.3g", f.cell_dx_over_d) + " wide, " + fmt("%.3g", f.cell_dy_over_d) + " high");
    const auto& cp = s.coupling;
    const double dx = f.cell_dx, dy = f.cell_dy;
    line("void fraction",
         cp.void_fraction == VoidFraction::Smoothed
             ? fmt("smoothed over %.3g m", cp.void_fraction_length) + " (" +
                   fmt("%.3g", cp.void_fraction_length / dx) +
                   " cells wide, " +
                   fmt("%.3g", cp.void_fraction_length / dy) +
                   " high; " + fmt("%.3g d", cp.void_fraction_length / s.particles.diameter) + ")"
             : std::string("each cell's exact share of the spheres (eq 22)"));
    if (s.inlet.plenum_height > 0.0)
      line("plenum", fmt("%.3g m", s.inlet.plenum_height) + " of gas under the floor (" +
                         fmt("%.3g", s.inlet.plenum_height / dy) + " cells)");
    if (s.inlet.distributor_resistance > 0.0) {
      const double drop = s.inlet.distributor_resistance * s.inlet.superficial_velocity;
      line("distributor plate", fmt("%.4g Pa s/m", s.inlet.distributor_resistance) + ": " +
                                    fmt("%.4g Pa", drop) + " at U (" +
                                    fmt("%.3g", drop / f.weight_per_area) + " W/A)");
    }
    line("gas step dt_gas",
         fmt("%.4g s", f.gas_dt) + " (time.dt x coupling.particle_steps_per_gas_step)");
    line("gas CFL at the jet velocity", fmt("%.3g", f.gas_cfl_at_jet) +
                                            " (u_jet dt_gas / min(dx, dy); "
                                            "a gas step past 0.8 is taken early)");
  } else {
    line("gas", "none");
  }
  for (const auto& w : c.warnings) o << "warning: " << w << "\n";
  for (const auto& r : c.refusals) o << "refused: " << r << "\n";
  if (c.warnings.empty() && c.refusals.empty()) o << "no warnings\n";
  return o.str();
}

namespace {
// The last scene checked before a run: its warnings and what the gas hint needs.
struct Hint {
  std::vector<std::string> warnings;
  bool gas = false;
  double superficial_velocity = 0.0, jet_velocity = 0.0, dt = 0.0;
};
std::mutex hint_mutex;
Hint hint;

bool mentions(const std::string& text, const char* word) {
  return text.find(word) != std::string::npos;
}
}  // namespace

void refuse_unsafe_scene(const Settings& s) {
  const SceneCheck c = check_scene(s);
  {
    const std::lock_guard lock(hint_mutex);
    hint = {c.warnings, c.figures.gas, s.inlet.superficial_velocity, c.figures.jet_velocity,
            s.time.dt};
  }
  if (!c.refusals.empty()) throw InputError(c.refusals.front() + " (see: fluidbed check)");
}

std::string failure_hint(const std::string& failure, double velocity_in_use) {
  const std::lock_guard lock(hint_mutex);
  const std::string head = "; likely cause: ";
  if (mentions(failure, "CFL")) {
    // The gas outran its step: the gas velocity crossed the limit, whatever the contacts.
    const bool scenes = velocity_in_use < 0.0 || velocity_in_use == hint.superficial_velocity;
    if (scenes)
      for (const std::string& w : hint.warnings)
        if (mentions(w, "CFL")) return head + w;
    if (!hint.gas) return "";
    const std::string tail = ", faster than the gas can be followed in a step; lower " +
                             std::string(scenes ? "inlet.superficial_velocity" : "the velocity") +
                             ", or time.dt (now " + fmt("%.3g s", hint.dt) + ")";
    if (scenes)
      return head + "the gas velocity: the jet enters at " + fmt("%.3g m/s", hint.jet_velocity) +
             " (inlet.superficial_velocity = " + fmt("%.3g m/s", hint.superficial_velocity) +
             ")" + tail;
    // A control changed the velocity: the jet's is in proportion (the inlet over the slots).
    const std::string jet =
        hint.superficial_velocity > 0.0
            ? "the jet enters at " +
                  fmt("%.3g m/s", hint.jet_velocity * velocity_in_use / hint.superficial_velocity) +
                  " ("
            : "(";
    return head + "the gas velocity: " + jet + fmt("%.3g m/s", velocity_in_use) +
           " superficial in use; the scene's inlet.superficial_velocity is " +
           fmt("%.3g m/s", hint.superficial_velocity) + ")" + tail;
  }
  for (const std::string& w : hint.warnings)
    if (mentions(w, "time.dt") || mentions(w, "contact.")) return head + w;
  return hint.warnings.empty() ? std::string() : head + hint.warnings.front();
}

}  // namespace fluidbed
