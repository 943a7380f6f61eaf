#include "run/run_loop.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"

namespace fluidbed {

void check_gas_step(const Simulation& sim, const RunOptions& o) {
  const double cfl = sim.coupling_diagnostics().gas.max_cfl;
  if (!(cfl <= o.cfl_limit)) {
    std::ostringstream os;
    os.precision(4);
    os << "gas CFL number " << cfl << " above the limit " << o.cfl_limit << " at t = " << sim.time()
       << " s: the gas step (time.dt x coupling.particle_steps_per_gas_step) is "
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
      os << "particle " << sim.dem().id_of(i)
         << " starts with a non-finite position or velocity (NaN) at t = " << sim.time() << " s";
      throw SimulationFailure(os.str());
    }
}

RunResult run_simulation(Simulation& sim, const RunOptions& options) {
  const Settings& s = sim.settings();
  const double until = options.until >= 0.0 ? options.until : s.time.end;
  const std::int64_t last_step = steps_for(until, s.time.dt);
  RunRecorder recorder(sim, last_step, options.bubbles);

  const auto wall_start = std::chrono::steady_clock::now();
  auto next_progress = options.progress_interval;
  auto wall_now = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };

  check_start(sim);
  if (options.restore) options.restore(recorder);
  // A resumed run's rows so far are the caller's already.
  std::size_t rows_handed = recorder.rows().size();
  const std::int64_t first_step = sim.steps();
  double next_checkpoint = options.checkpoint_interval;
  RunResult result;
  while (sim.steps() < last_step) {
    sim.step();
    if (recorder.after_step(sim)) check_gas_step(sim, options);
    if (options.on_row)
      for (; rows_handed < recorder.rows().size(); ++rows_handed)
        options.on_row(recorder.rows()[rows_handed]);
    if (options.on_step) options.on_step(sim);
    if (options.stop && options.stop()) {
      result.completed = false;
      if (options.checkpoint) options.checkpoint(sim, recorder, options.wall_before + wall_now());
      break;
    }
    if (options.checkpoint && options.checkpoint_interval > 0.0 && (sim.steps() & 63) == 0 &&
        sim.steps() < last_step) {
      const double w = wall_now();
      if (w >= next_checkpoint) {
        // The whole run's wall time projected from this part's pace.
        const double done = static_cast<double>(sim.steps() - first_step);
        const double total = w * static_cast<double>(last_step - first_step) / done;
        if (options.wall_before + total > options.checkpoint_min_run)
          options.checkpoint(sim, recorder, options.wall_before + w);
        next_checkpoint = w + options.checkpoint_interval;
      }
    }
    if (options.progress && (sim.steps() & 255) == 0) {
      const double w = wall_now();
      if (w >= next_progress) {
        options.progress(sim, w);
        next_progress = w + options.progress_interval;
      }
    }
  }
  result.summary = recorder.summary(sim, options.wall_before + wall_now());
  result.dp_spectrum = recorder.dp_spectrum();
  result.probes = recorder.probes();
  result.probe_spectra = recorder.probe_spectra();
  result.rows = recorder.take_rows();
  if (BubbleRecorder* b = recorder.bubbles()) {
    result.bubbles = true;
    result.bubble_rows = b->take_rows();
    result.mixing = b->mixing();
  }
  return result;
}

namespace {

// Every column of timeseries.csv, in order: its name and its value in a row, each with its
// printf format. The header and the rows are both written from this one list. `probes`: the
// number of probe columns (a row's own count of probe values).
template <class F>
void timeseries_columns(const TimeseriesRow& r, bool bubbles, std::size_t probes, F&& column) {
  const EnergyBudget& e = r.energy;
  column("t", "%.9g", r.t);
  column("dp", "%.9g", r.dp);
  column("max_overlap_ratio", "%.6g", r.max_overlap_ratio);
  column("max_wall_overlap_ratio", "%.6g", r.max_wall_overlap_ratio);
  column("kinetic_energy", "%.9g", r.kinetic_energy);
  column("contacts", "%d", r.pair_contacts + r.wall_contacts);
  column("pair_contacts", "%d", r.pair_contacts);
  column("wall_contacts", "%d", r.wall_contacts);
  column("simple_iterations", "%d", r.simple_iterations);
  column("mass_residual", "%.3g", r.mass_residual);
  column("max_cfl", "%.4g", r.max_cfl);
  column("fluid_force_y", "%.6g", r.fluid_force_y);
  column("e_kinetic", "%.9g", e.kinetic_translation);
  column("e_rotation", "%.9g", e.kinetic_rotation);
  column("e_potential", "%.9g", e.potential);
  column("e_spring_n", "%.9g", e.spring_normal);
  column("e_spring_t", "%.9g", e.spring_tangential);
  column("w_gas", "%.9g", e.gas_work);
  column("e_dashpot", "%.9g", e.dashpot);
  column("e_friction", "%.9g", e.friction);
  column("e_residual", "%.6g", e.residual);
  column("bed_height", "%.6g", r.bed_height);
  column("bed_top", "%.6g", r.bed_top);
  for (std::size_t k = 0; k < probes; ++k)
    column(("p_probe_" + std::to_string(k + 1)).c_str(), "%.9g",
           k < r.probes.size() ? r.probes[k] : 0.0);
  if (bubbles) {
    column("bubbles", "%d", r.bubbles);
    column("regime", "%s", to_string(r.regime));
  }
}

}  // namespace

std::string timeseries_header(bool bubbles, std::size_t probes) {
  std::string h;
  timeseries_columns(TimeseriesRow{}, bubbles, probes,
                     [&](const char* name, const char*, const auto&) {
                       h += h.empty() ? "" : ",";
                       h += name;
                     });
  return h + "\n";
}

std::string timeseries_line(const TimeseriesRow& row, bool bubbles) {
  std::string csv;
  char value[64];
  timeseries_columns(row, bubbles, row.probes.size(),
                     [&](const char*, const char* format, const auto& v) {
                       std::snprintf(value, sizeof value, format, v);
                       csv += csv.empty() ? "" : ",";
                       csv += value;
                     });
  return csv + "\n";
}

void write_run_outputs(const std::string& dir, const RunResult& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("cannot create output folder " + dir + ": " + ec.message());
  std::string csv = timeseries_header(r.bubbles, r.probes.size());
  for (const auto& row : r.rows) csv += timeseries_line(row, r.bubbles);
  const std::filesystem::path d(dir);
  write_file_atomically((d / "timeseries.csv").string(), [&](std::ostream& o) { o << csv; });
  if (r.dp_spectrum.ok)
    write_file_atomically((d / "dp_spectrum.csv").string(), [&](std::ostream& o) {
      std::vector<SpectrumColumn> probes;
      for (std::size_t k = 0; k < r.probe_spectra.size(); ++k)
        probes.push_back({"psd_probe_" + std::to_string(k + 1), &r.probe_spectra[k]});
      write_spectrum_csv(o, r.dp_spectrum, probes);
    });
  if (r.bubbles) {
    write_file_atomically((d / "bubbles.csv").string(), [&](std::ostream& o) {
      write_bubbles_csv_header(o);
      write_bubbles_csv_rows(o, r.bubble_rows);
    });
    write_file_atomically((d / "mixing.csv").string(), [&](std::ostream& o) {
      o << "t,lacey_index\n";
      char buf[64];
      for (const MixingSample& m : r.mixing) {
        std::snprintf(buf, sizeof buf, "%.9g,%.6g\n", m.t, m.index);
        o << buf;
      }
    });
  }
  write_file_atomically((d / "summary.json").string(),
                        [&](std::ostream& o) { o << r.summary.dump(2) << "\n"; });
}

}  // namespace fluidbed
