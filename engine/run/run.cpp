#include "run/run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"
#include "analysis/bounce_tracker.hpp"
#include "analysis/cycles.hpp"
#include "analysis/packing_metrics.hpp"

namespace fluidbed {
namespace {

// RunOptions' checks after a gas step (see run.hpp).
void check_gas_step(const Simulation& sim, const RunOptions& o) {
  const double cfl = sim.coupling_diagnostics().gas.max_cfl;
  if (!(cfl <= o.cfl_limit)) {
    std::ostringstream os;
    os.precision(4);
    os << "gas CFL number " << cfl << " above the limit " << o.cfl_limit << " at t = "
       << sim.time() << " s: the gas step (time.dt x coupling.particle_steps_per_gas_step) is "
       << "too long for the gas velocity";
    throw SimulationFailure(os.str());
  }
  const std::vector<double>& eps = sim.coupler()->porosity();
  const int nx = sim.settings().gas.cells_x;
  for (std::size_t c = 0; c < eps.size(); ++c)
    if (!(eps[c] >= o.porosity_min && eps[c] <= 1.0 + 1e-12)) {
      std::ostringstream os;
      os.precision(4);
      os << "porosity " << eps[c] << " in gas cell (" << c % static_cast<std::size_t>(nx) << ", "
         << c / static_cast<std::size_t>(nx) << ") at t = " << sim.time() << " s is outside ["
         << o.porosity_min << ", 1]: particles overlap far more than a packing allows";
      throw SimulationFailure(os.str());
    }
}

// A starting state that is not finite (a NaN from a state file or a setting) is refused before
// the first step, which could not even sort it into the neighbour grid.
void check_start(const Simulation& sim) {
  const Particles& p = sim.dem().particles();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!std::isfinite(p.x[i] + p.y[i] + p.vx[i] + p.vy[i] + p.w[i])) {
      std::ostringstream os;
      os << "particle " << i << " starts with a non-finite position or velocity (NaN) at t = "
         << sim.time() << " s";
      throw SimulationFailure(os.str());
    }
}

}  // namespace

RunResult run_simulation(Simulation& sim, const RunOptions& options) {
  const Settings& s = sim.settings();
  const double dt = s.time.dt;
  const double until = options.until >= 0.0 ? options.until : s.time.end;
  const auto last_step = steps_for(until, dt);
  const auto row_every =
      std::max<std::int64_t>(1, steps_for(s.diagnostics.output_interval, dt));
  const double startup = s.diagnostics.averaging_start;

  std::optional<BounceTracker> bounces;
  if (s.scene.kind == "drop") bounces.emplace(sim.dem(), s.physics.gravity);

  RunResult result;
  double max_overlap = 0.0, max_overlap_after = 0.0, ke_peak = 0.0;
  double dp_sum = 0.0, dp_sq = 0.0, dp_max = -INFINITY, dp_max_time = 0.0;
  std::int64_t dp_samples = 0;
  // Gas solver and coupling statistics.
  std::int64_t gas_steps = 0, simple_sum = 0, pressure_sum = 0, not_converged = 0;
  int simple_max = 0;
  double residual_max = 0.0, cfl_max = 0.0, third_law_max = 0.0;
  double fluid_fx_sum = 0.0, fluid_fy_sum = 0.0;
  std::int64_t fluid_samples = 0;
  double bed_height_sum = 0.0;  // m, summed over the rows after start-up (beds)
  std::int64_t bed_height_samples = 0;
  int last_gas_steps = sim.has_gas() ? sim.coupling_diagnostics().gas_steps : 0;
  TimeseriesRow pending;
  const std::int64_t first_step = sim.steps();

  const auto wall_start = std::chrono::steady_clock::now();
  auto next_progress = options.progress_interval;
  auto wall_now = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };

  check_start(sim);
  while (sim.steps() < last_step) {
    sim.step();
    const StepDiagnostics& d = sim.dem().diagnostics();
    const double t = sim.time();
    max_overlap = std::max(max_overlap, d.max_overlap_ratio);
    if (t > startup) max_overlap_after = std::max(max_overlap_after, d.max_overlap_ratio);
    ke_peak = std::max(ke_peak, d.kinetic_energy);
    pending.max_overlap_ratio = std::max(pending.max_overlap_ratio, d.max_overlap_ratio);
    pending.max_wall_overlap_ratio =
        std::max(pending.max_wall_overlap_ratio, d.max_wall_overlap_ratio);
    if (sim.has_gas()) {
      const double dp = sim.pressure_drop();
      const CouplingDiagnostics& c = sim.coupling_diagnostics();
      if (c.gas_steps != last_gas_steps) {
        last_gas_steps = c.gas_steps;
        ++gas_steps;
        simple_sum += c.gas.simple_iterations;
        simple_max = std::max(simple_max, c.gas.simple_iterations);
        pressure_sum += c.gas.pressure_iterations_total;
        not_converged += c.gas.converged ? 0 : 1;
        residual_max = std::max(residual_max, c.gas.mass_residual);
        cfl_max = std::max(cfl_max, c.gas.max_cfl);
        third_law_max = std::max(third_law_max, c.third_law_error);
        pending.max_cfl = std::max(pending.max_cfl, c.gas.max_cfl);
        check_gas_step(sim, options);
      }
      if (t > startup) {
        dp_sum += dp;
        dp_sq += dp * dp;
        ++dp_samples;
      }
    }
    if (bounces) bounces->observe(sim.dem());
    if (sim.steps() % row_every == 0 || sim.steps() == last_step) {
      pending.t = t;
      pending.dp = sim.pressure_drop();
      // The start-up peak from the sampled dp: the first gas step's pulse (the incompressible
      // column set moving in one step, about rho_f H U / dt) is no measurement of the bed.
      if (sim.has_gas() && pending.dp > dp_max) {
        dp_max = pending.dp;
        dp_max_time = t;
      }
      pending.kinetic_energy = d.kinetic_energy;
      pending.pair_contacts = d.pair_contacts;
      pending.wall_contacts = d.wall_contacts;
      if (sim.has_gas()) {
        pending.simple_iterations = sim.coupling_diagnostics().gas.simple_iterations;
        pending.mass_residual = sim.coupling_diagnostics().gas.mass_residual;
        // Sampled at the rows only: a loop over every particle at every step would cost as
        // much as a fifth of a step and pull each thread's particles to one core.
        double fx = 0.0, fy = 0.0;
        for (double f : sim.dem().particles().ext_fx) fx += f;
        for (double f : sim.dem().particles().ext_fy) fy += f;
        pending.fluid_force_y = fy;
        if (t > startup) {
          fluid_fx_sum += fx;
          fluid_fy_sum += fy;
          ++fluid_samples;
        }
      }
      if (t > startup && s.scene.kind == "bed") {
        bed_height_sum += measure_packing(sim.dem().particles(), s.domain.width, s.domain.thickness).bed_height;
        ++bed_height_samples;
      }
      result.rows.push_back(pending);
      pending = TimeseriesRow{};
    }
    if (options.on_step) options.on_step(sim);
    if (options.progress && (sim.steps() & 255) == 0) {
      const double w = wall_now();
      if (w >= next_progress) {
        options.progress(sim, w);
        next_progress = w + options.progress_interval;
      }
    }
  }
  const double wall = wall_now();

  const Particles& p = sim.dem().particles();
  const std::int64_t steps = sim.steps() - first_step;
  const double sim_time = static_cast<double>(steps) * dt;
  double mass = 0.0;
  for (double m : p.mass) mass += m;

  nlohmann::json& j = result.summary;
  j["status"] = "completed";
  j["scene"] = s.scene.name;
  j["kind"] = s.scene.kind;
  j["particles"] = p.size();
  j["steps"] = steps;
  j["dt_s"] = dt;
  j["sim_time_s"] = sim_time;
  j["end_time_s"] = sim.time();
  j["wall_time_s"] = wall;
  j["wall_s_per_sim_s"] = sim_time > 0.0 ? wall / sim_time : 0.0;
  j["particle_steps_per_s"] =
      wall > 0.0 ? static_cast<double>(steps) * static_cast<double>(p.size()) / wall : 0.0;
  j["integrator"] = s.time.integrator;
  j["contact_displacement"] = s.contact.displacement;
  j["gas"] = sim.has_gas();
  j["averaging_start_s"] = startup;
  j["dp_mean_pa"] = dp_samples > 0 ? nlohmann::json(dp_sum / static_cast<double>(dp_samples))
                                   : nlohmann::json(nullptr);
  j["dp_max_pa"] = sim.has_gas() ? nlohmann::json(dp_max) : nlohmann::json(nullptr);
  if (sim.has_gas()) {
    const double n = static_cast<double>(std::max<std::int64_t>(dp_samples, 1));
    const double mean = dp_sum / n;
    j["dp_max_time_s"] = dp_max_time;
    j["dp_std_pa"] = std::sqrt(std::max(dp_sq / n - mean * mean, 0.0));
    const double nf = static_cast<double>(std::max<std::int64_t>(fluid_samples, 1));
    j["fluid_force_mean_n"] = {fluid_fx_sum / nf, fluid_fy_sum / nf};
    const GasSolver& g = *sim.gas();
    j["superficial_velocity_m_s"] = g.superficial_velocity();
    j["jet_velocity_m_s"] = g.jet_velocity();
    j["inlet"] = s.inlet.kind;
    j["pressure_gradient_force"] = s.coupling.pressure_gradient_force;
    j["particle_steps_per_gas_step"] = s.coupling.particle_steps_per_gas_step;
    j["gas_steps"] = gas_steps;
    j["simple_iterations_mean"] =
        gas_steps > 0 ? static_cast<double>(simple_sum) / static_cast<double>(gas_steps) : 0.0;
    j["simple_iterations_max"] = simple_max;
    j["pressure_iterations_mean"] =
        gas_steps > 0 ? static_cast<double>(pressure_sum) / static_cast<double>(gas_steps) : 0.0;
    j["gas_steps_not_converged"] = not_converged;
    j["mass_residual_max"] = residual_max;
    j["max_cfl"] = cfl_max;
    j["third_law_error_max"] = third_law_max;
    // How regular dp is after start-up (Figs 16-17): dominant period and cycle-length spread.
    std::vector<double> ts, dps;
    for (const auto& row : result.rows)
      if (row.t > startup) {
        ts.push_back(row.t);
        dps.push_back(row.dp);
      }
    const CycleStats cyc = analyse_cycles(ts, dps);
    j["dp_dominant_period_s"] = cyc.ok ? nlohmann::json(cyc.dominant_period) : nlohmann::json(nullptr);
    j["dp_dominant_power_share"] = cyc.dominant_power_share;
    j["dp_cycles"] = cyc.cycles;
    j["dp_cycle_length_mean_s"] = cyc.cycle_mean;
    j["dp_cycle_length_cv"] = cyc.cycle_cv;
  }
  j["bed_weight_per_area_pa"] = mass * s.physics.gravity / (s.domain.width * s.domain.thickness);
  j["max_overlap_ratio"] = max_overlap;
  j["max_overlap_ratio_after_startup"] = max_overlap_after;
  j["max_overlap_ratio_final"] = sim.dem().diagnostics().max_overlap_ratio;
  j["kinetic_energy_peak_j"] = ke_peak;
  j["kinetic_energy_final_j"] = sim.dem().diagnostics().kinetic_energy;
  j["contacts_final"] = sim.dem().diagnostics().pair_contacts + sim.dem().diagnostics().wall_contacts;
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sim.state_hash()));
  j["state_hash"] = hash;

  if (bounces) {
    const auto& e = bounces->restitutions();
    const auto apex = bounces->apex_heights();
    j["restitution"] = e.empty() ? nlohmann::json(nullptr) : nlohmann::json(e.front());
    j["rebound_height_ratio"] =
        apex.empty() ? nlohmann::json(nullptr) : nlohmann::json(apex.front() / bounces->drop_height());
    j["drop_height_m"] = bounces->drop_height();
    j["bounce_restitutions"] = e;
    j["bounce_heights_m"] = apex;
  }
  if (bed_height_samples > 0)  // the bubbling bed's mean height after start-up (rows)
    j["bed_height_mean_m"] = bed_height_sum / static_cast<double>(bed_height_samples);
  if (s.scene.kind == "packing" || s.scene.kind == "bed") {
    const PackingMetrics m = measure_packing(p, s.domain.width, s.domain.thickness);
    j["bed_height_m"] = m.bed_height;
    j["solid_fraction"] = m.solid_fraction;
  }
  return result;
}

void write_run_outputs(const std::string& dir, const RunResult& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("cannot create output folder " + dir + ": " + ec.message());
  std::string csv =
      "t,dp,max_overlap_ratio,max_wall_overlap_ratio,kinetic_energy,contacts,pair_contacts,"
      "wall_contacts,simple_iterations,mass_residual,max_cfl,fluid_force_y\n";
  char line[256];
  for (const auto& row : r.rows) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.6g,%.6g,%.9g,%d,%d,%d,%d,%.3g,%.4g,%.6g\n",
                  row.t, row.dp, row.max_overlap_ratio, row.max_wall_overlap_ratio,
                  row.kinetic_energy, row.pair_contacts + row.wall_contacts, row.pair_contacts,
                  row.wall_contacts, row.simple_iterations, row.mass_residual, row.max_cfl,
                  row.fluid_force_y);
    csv += line;
  }
  const std::filesystem::path d(dir);
  write_file_atomically((d / "timeseries.csv").string(), [&](std::ostream& o) { o << csv; });
  write_file_atomically((d / "summary.json").string(),
                        [&](std::ostream& o) { o << r.summary.dump(2) << "\n"; });
}

}  // namespace fluidbed
