#include "sim/run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "core/errors.hpp"
#include "experiments/bounce_tracker.hpp"
#include "experiments/packing_metrics.hpp"

namespace fluidbed {

RunResult run_simulation(Simulation& sim, const RunOptions& options) {
  const Settings& s = sim.settings();
  const double dt = s.time.dt;
  const double until = options.until >= 0.0 ? options.until : s.time.end;
  const auto last_step = static_cast<std::int64_t>(std::llround(until / dt));
  const auto row_every =
      std::max<std::int64_t>(1, std::llround(s.diagnostics.output_interval / dt));
  const double startup = s.diagnostics.averaging_start;

  std::optional<BounceTracker> bounces;
  if (s.scene.kind == "drop") bounces.emplace(sim.dem(), s.physics.gravity);

  RunResult result;
  double max_overlap = 0.0, max_overlap_after = 0.0, ke_peak = 0.0;
  double dp_sum = 0.0, dp_max = -INFINITY;
  std::int64_t dp_samples = 0;
  TimeseriesRow pending;
  const std::int64_t first_step = sim.steps();

  const auto wall_start = std::chrono::steady_clock::now();
  auto next_progress = options.progress_interval;
  auto wall_now = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };

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
      dp_max = std::max(dp_max, dp);
      if (t > startup) {
        dp_sum += dp;
        ++dp_samples;
      }
    }
    if (bounces) bounces->observe(sim.dem());
    if (sim.steps() % row_every == 0 || sim.steps() == last_step) {
      pending.t = t;
      pending.dp = sim.pressure_drop();
      pending.kinetic_energy = d.kinetic_energy;
      pending.pair_contacts = d.pair_contacts;
      pending.wall_contacts = d.wall_contacts;
      result.rows.push_back(pending);
      pending = TimeseriesRow{};
    }
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
  if (s.scene.kind == "packing" || s.scene.kind == "bed") {
    const PackingMetrics m = measure_packing(p, s.domain.width, s.domain.thickness);
    j["bed_height_m"] = m.bed_height;
    j["solid_fraction"] = m.solid_fraction;
  }
  return result;
}

namespace {

void write_atomically(const std::filesystem::path& path, const std::string& text) {
  const auto tmp = path.string() + ".partial";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out) throw InputError("cannot write " + path.string());
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

void write_run_outputs(const std::string& dir, const RunResult& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("cannot create output folder " + dir + ": " + ec.message());
  std::string csv =
      "t,dp,max_overlap_ratio,max_wall_overlap_ratio,kinetic_energy,contacts,pair_contacts,"
      "wall_contacts\n";
  char line[256];
  for (const auto& row : r.rows) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.6g,%.6g,%.9g,%d,%d,%d\n", row.t, row.dp,
                  row.max_overlap_ratio, row.max_wall_overlap_ratio, row.kinetic_energy,
                  row.pair_contacts + row.wall_contacts, row.pair_contacts, row.wall_contacts);
    csv += line;
  }
  const std::filesystem::path d(dir);
  write_atomically(d / "timeseries.csv", csv);
  write_atomically(d / "summary.json", r.summary.dump(2) + "\n");
}

}  // namespace fluidbed
