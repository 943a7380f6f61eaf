#include "run/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <type_traits>

#include "analysis/cycles.hpp"
#include "analysis/packing_metrics.hpp"
#include "analysis/pressure_probe.hpp"
#include "core/steps.hpp"

namespace fluidbed {

RunRecorder::RunRecorder(const Simulation& sim, std::int64_t last_step, bool bubbles)
    : first_step_(sim.steps()), last_step_(last_step) {
  const Settings& s = sim.settings();
  row_every_ = std::max<std::int64_t>(1, steps_for(s.diagnostics.output_interval, s.time.dt));
  startup_ = s.diagnostics.averaging_start;
  bed_ = s.scene.kind == SceneKind::Bed;
  if (s.scene.kind == SceneKind::Drop) bounces_.emplace(sim.dem(), s.physics.gravity);
  last_gas_steps_ = sim.has_gas() ? sim.coupling_diagnostics().gas_steps : 0;
  has_gas_ = sim.has_gas();
  if (has_gas_) probes_ = s.diagnostics.probes;  // the scene check refuses probes without gas
  energy_start_ = energy_state(sim.dem(), s.physics.gravity);
  ledger_start_ = sim.dem().energy_ledger();
  if (bubbles) {
    bubbles_.emplace(sim);
    bubbles_->analyse(sim);
  }
}

void RunRecorder::gas_step_done(const CouplingDiagnostics& c) {
  last_gas_steps_ = c.gas_steps;
  ++gas_steps_;
  simple_sum_ += c.gas.simple_iterations;
  simple_max_ = std::max(simple_max_, c.gas.simple_iterations);
  pressure_sum_ += c.gas.pressure_iterations_total;
  not_converged_ += c.gas.converged ? 0 : 1;
  split_gas_steps_ += c.gas.substeps > 1 ? 1 : 0;
  residual_max_ = std::max(residual_max_, c.gas.mass_residual);
  cfl_max_ = std::max(cfl_max_, c.gas.max_cfl);
  third_law_max_ = std::max(third_law_max_, c.third_law_error);
  pending_.max_cfl = std::max(pending_.max_cfl, c.gas.max_cfl);
}

bool RunRecorder::after_step(const Simulation& sim) {
  const StepDiagnostics& d = sim.dem().diagnostics();
  const double t = sim.time();
  max_overlap_ = std::max(max_overlap_, d.max_overlap_ratio);
  if (t > startup_) max_overlap_after_ = std::max(max_overlap_after_, d.max_overlap_ratio);
  ke_peak_ = std::max(ke_peak_, d.kinetic_energy);
  pending_.max_overlap_ratio = std::max(pending_.max_overlap_ratio, d.max_overlap_ratio);
  pending_.max_wall_overlap_ratio = std::max(pending_.max_wall_overlap_ratio, d.max_wall_overlap_ratio);
  bool gas_stepped = false;
  if (sim.has_gas()) {
    const CouplingDiagnostics& c = sim.coupling_diagnostics();
    if (c.gas_steps != last_gas_steps_) {
      gas_step_done(c);
      gas_stepped = true;
    }
    if (t > startup_) {
      const double dp = sim.pressure_drop();
      dp_sum_ += dp;
      dp_sq_ += dp * dp;
      ++dp_samples_;
    }
  }
  if (bounces_) bounces_->observe(sim.dem());
  if (bubbles_) bubbles_->after_step(sim);
  if (sim.steps() % row_every_ == 0 || sim.steps() == last_step_) write_row(sim);
  return gas_stepped;
}

void RunRecorder::write_row(const Simulation& sim) {
  const StepDiagnostics& d = sim.dem().diagnostics();
  const double t = sim.time();
  pending_.t = t;
  pending_.dp = sim.pressure_drop();
  // The start-up peak from the sampled dp: the first gas step's pulse (the incompressible
  // column set moving in one step, about rho_f H U / dt) is no measurement of the bed.
  if (sim.has_gas() && pending_.dp > dp_max_) {
    dp_max_ = pending_.dp;
    dp_max_time_ = t;
  }
  pending_.kinetic_energy = d.kinetic_energy;
  pending_.energy = energy_budget(sim.dem(), sim.settings().physics.gravity, energy_start_, ledger_start_);
  pending_.pair_contacts = d.pair_contacts;
  pending_.wall_contacts = d.wall_contacts;
  if (sim.has_gas()) {
    pending_.simple_iterations = sim.coupling_diagnostics().gas.simple_iterations;
    pending_.mass_residual = sim.coupling_diagnostics().gas.mass_residual;
    // Sampled at the rows only: a loop over every particle at every step would cost as much
    // as a fifth of a step and pull each thread's particles to one core.
    double fx = 0.0, fy = 0.0;
    for (double f : sim.dem().particles().ext_fx) fx += f;
    for (double f : sim.dem().particles().ext_fy) fy += f;
    pending_.fluid_force_y = fy;
    if (t > startup_) {
      fluid_fx_sum_ += fx;
      fluid_fy_sum_ += fy;
      ++fluid_samples_;
    }
  }
  {
    const Settings& s = sim.settings();
    pending_.bed_height =
        measure_packing(sim.dem().particles(), s.domain.width, s.domain.thickness).bed_height;
    if (t > startup_ && bed_) {
      bed_height_sum_ += pending_.bed_height;
      ++bed_height_samples_;
    }
    pending_.bed_top = bed_top(sim.dem().particles());
  }
  if (!probes_.empty()) {
    const GasSolver& g = *sim.gas();
    pending_.probes.clear();
    for (const ProbePoint& q : probes_)
      pending_.probes.push_back(probe_pressure(g.grid(), g.pressure(), q.x, q.y));
  }
  if (bubbles_) {
    pending_.bubbles = bubbles_->bubbles_now();
    pending_.regime = bubbles_->regime_now();
  }
  rows_.push_back(pending_);
  pending_ = TimeseriesRow{};
}

template <class Column>
std::vector<double> RunRecorder::after_startup(Column&& column) const {
  std::vector<double> v;
  for (const auto& row : rows_)
    if (row.t > startup_) v.push_back(column(row));
  return v;
}

std::vector<double> RunRecorder::times_after_startup() const {
  return after_startup([](const TimeseriesRow& r) { return r.t; });
}

PowerSpectrum RunRecorder::spectrum_after_startup(const std::vector<double>& series) const {
  if (rows_.size() < 2) return PowerSpectrum{};
  // The rows are one output interval apart, the last one possibly shorter (the run's end).
  const double interval = rows_[1].t - rows_[0].t;
  if (series.size() < 8 || !(interval > 0.0)) return PowerSpectrum{};
  return welch_spectrum(series, interval);
}

nlohmann::json RunRecorder::summary(const Simulation& sim, double wall) const {
  const Settings& s = sim.settings();
  const double dt = s.time.dt;
  const Particles& p = sim.dem().particles();
  const std::int64_t steps = sim.steps() - first_step_;
  const double sim_time = static_cast<double>(steps) * dt;
  double mass = 0.0;
  for (double m : p.mass) mass += m;

  nlohmann::json j;
  j["status"] = "completed";
  j["scene"] = s.scene.name;
  j["kind"] = option_string(s.scene.kind);
  j["particles"] = p.size();
  j["steps"] = steps;
  j["dt_s"] = dt;
  j["sim_time_s"] = sim_time;
  j["end_time_s"] = sim.time();
  j["wall_time_s"] = wall;
  j["wall_s_per_sim_s"] = sim_time > 0.0 ? wall / sim_time : 0.0;
  j["particle_steps_per_s"] =
      wall > 0.0 ? static_cast<double>(steps) * static_cast<double>(p.size()) / wall : 0.0;
  j["integrator"] = option_string(s.time.integrator);
  j["contact_displacement"] = option_string(s.contact.displacement);
  j["gas"] = sim.has_gas();
  j["averaging_start_s"] = startup_;
  j["dp_mean_pa"] = dp_samples_ > 0 ? nlohmann::json(dp_sum_ / static_cast<double>(dp_samples_))
                                    : nlohmann::json(nullptr);
  j["dp_max_pa"] = sim.has_gas() ? nlohmann::json(dp_max_) : nlohmann::json(nullptr);
  if (sim.has_gas()) add_gas_summary(sim, j);
  j["bed_weight_per_area_pa"] = mass * s.physics.gravity / (s.domain.width * s.domain.thickness);
  j["max_overlap_ratio"] = max_overlap_;
  j["max_overlap_ratio_after_startup"] = max_overlap_after_;
  j["max_overlap_ratio_final"] = sim.dem().diagnostics().max_overlap_ratio;
  j["kinetic_energy_peak_j"] = ke_peak_;
  j["kinetic_energy_final_j"] = sim.dem().diagnostics().kinetic_energy;
  j["energy"] = energy_summary(
      energy_start_, energy_budget(sim.dem(), s.physics.gravity, energy_start_, ledger_start_), sim_time);
  j["contacts_final"] = sim.dem().diagnostics().pair_contacts + sim.dem().diagnostics().wall_contacts;
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sim.state_hash()));
  j["state_hash"] = hash;
  if (bounces_) add_drop_summary(j);
  if (bubbles_) {
    j["bubbles"] = bubbles_->bubbles_summary(startup_);
    j["mixing"] = bubbles_->mixing_summary();
  }
  if (bed_height_samples_ > 0)  // the bubbling bed's mean height after start-up (rows)
    j["bed_height_mean_m"] = bed_height_sum_ / static_cast<double>(bed_height_samples_);
  if (has_gas_ || bed_) add_bed_top_summary(j);
  if (!probes_.empty()) j["probes"] = probes_summary();
  if (s.scene.kind == SceneKind::Packing || s.scene.kind == SceneKind::Bed) {
    const PackingMetrics m = measure_packing(p, s.domain.width, s.domain.thickness);
    j["bed_height_m"] = m.bed_height;
    j["solid_fraction"] = m.solid_fraction;
  }
  return j;
}

void RunRecorder::add_gas_summary(const Simulation& sim, nlohmann::json& j) const {
  const Settings& s = sim.settings();
  const double n = static_cast<double>(std::max<std::int64_t>(dp_samples_, 1));
  const double mean = dp_sum_ / n;
  j["dp_max_time_s"] = dp_max_time_;
  j["dp_std_pa"] = std::sqrt(std::max(dp_sq_ / n - mean * mean, 0.0));
  const double nf = static_cast<double>(std::max<std::int64_t>(fluid_samples_, 1));
  j["fluid_force_mean_n"] = {fluid_fx_sum_ / nf, fluid_fy_sum_ / nf};
  const GasSolver& g = *sim.gas();
  j["superficial_velocity_m_s"] = g.superficial_velocity();
  j["jet_velocity_m_s"] = g.jet_velocity();
  j["inlet"] = option_string(s.inlet.kind);
  j["pressure_gradient_force"] = s.coupling.pressure_gradient_force;
  j["particle_steps_per_gas_step"] = s.coupling.particle_steps_per_gas_step;
  j["gas_steps"] = gas_steps_;
  const double gs = static_cast<double>(gas_steps_);
  j["simple_iterations_mean"] = gas_steps_ > 0 ? static_cast<double>(simple_sum_) / gs : 0.0;
  j["simple_iterations_max"] = simple_max_;
  j["pressure_iterations_mean"] = gas_steps_ > 0 ? static_cast<double>(pressure_sum_) / gs : 0.0;
  j["gas_steps_not_converged"] = not_converged_;
  j["gas_steps_split"] = split_gas_steps_;
  j["mass_residual_max"] = residual_max_;
  j["max_cfl"] = cfl_max_;
  j["third_law_error_max"] = third_law_max_;
  // How regular dp is after start-up (Figs 16-17): dominant period and cycle-length spread.
  const CycleStats cyc = analyse_cycles(
      times_after_startup(), after_startup([](const TimeseriesRow& r) { return r.dp; }));
  j["dp_spectrum"] = to_json(dp_spectrum());
  // The period only where it is a cycle (analysis/cycles.hpp); the highest peak's period always.
  j["dp_dominant_period_s"] =
      cyc.ok && cyc.regular ? nlohmann::json(cyc.dominant_period) : nlohmann::json(nullptr);
  j["dp_peak_period_s"] = cyc.ok ? nlohmann::json(cyc.dominant_period) : nlohmann::json(nullptr);
  j["dp_cycle"] = cyc.ok ? cyc.verdict : std::string("no regular cycle: record too short");
  j["dp_peak_prominence"] = cyc.ok && std::isfinite(cyc.peak_prominence) ? nlohmann::json(cyc.peak_prominence) : nlohmann::json(nullptr);
  j["dp_peak_amplitude_share"] = cyc.ok && std::isfinite(cyc.amplitude_share) ? nlohmann::json(cyc.amplitude_share) : nlohmann::json(nullptr);
  j["dp_dominant_power_share"] = cyc.dominant_power_share;
  j["dp_cycles"] = cyc.cycles;
  j["dp_cycle_length_mean_s"] = cyc.cycle_mean;
  j["dp_cycle_length_cv"] = cyc.cycle_cv;
}

PowerSpectrum RunRecorder::dp_spectrum() const {
  if (!has_gas_) return PowerSpectrum{};
  return spectrum_after_startup(after_startup([](const TimeseriesRow& r) { return r.dp; }));
}

std::vector<PowerSpectrum> RunRecorder::probe_spectra() const {
  std::vector<PowerSpectrum> out;
  for (std::size_t k = 0; k < probes_.size(); ++k)
    out.push_back(
        spectrum_after_startup(after_startup([k](const TimeseriesRow& r) { return r.probes[k]; })));
  return out;
}

namespace {

// Mean and standard deviation (population) of a series; null for none.
std::pair<nlohmann::json, nlohmann::json> mean_and_std(const std::vector<double>& v) {
  if (v.empty()) return {nullptr, nullptr};
  double sum = 0.0;
  for (double x : v) sum += x;
  const double mean = sum / static_cast<double>(v.size());
  double sq = 0.0;
  for (double x : v) sq += (x - mean) * (x - mean);
  return {mean, std::sqrt(sq / static_cast<double>(v.size()))};
}

// A spectrum's highest peak (Hz, refined), or null where it has none.
nlohmann::json peak_hz(const PowerSpectrum& p) {
  return p.ok && p.dominant_frequency_refined > 0.0 ? nlohmann::json(p.dominant_frequency_refined)
                                                    : nlohmann::json(nullptr);
}

}  // namespace

// The highest centre over the rows after start-up (the window of bed_height_mean_m): its mean,
// range and the highest peak of its spectrum; null when no row is after start-up.
void RunRecorder::add_bed_top_summary(nlohmann::json& j) const {
  const std::vector<double> top = after_startup([](const TimeseriesRow& r) { return r.bed_top; });
  j["bed_top_mean_m"] = mean_and_std(top).first;
  j["bed_top_min_m"] = top.empty() ? nlohmann::json(nullptr)
                                   : nlohmann::json(*std::min_element(top.begin(), top.end()));
  j["bed_top_max_m"] = top.empty() ? nlohmann::json(nullptr)
                                   : nlohmann::json(*std::max_element(top.begin(), top.end()));
  j["bed_top_peak_hz"] = peak_hz(spectrum_after_startup(top));
}

// Each probe after start-up: where it is, its mean and standard deviation, the highest peak of
// its spectrum and whether that peak is a regular cycle (analysis/cycles.hpp, the amplitude
// judged against the standard deviation: the mean of a pressure against the outlet is the weight
// of the bed above the probe, not a measure of its swings).
nlohmann::json RunRecorder::probes_summary() const {
  nlohmann::json list = nlohmann::json::array();
  const std::vector<double> ts = times_after_startup();
  const std::vector<PowerSpectrum> spectra = probe_spectra();
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const std::vector<double> p =
        after_startup([k](const TimeseriesRow& r) { return r.probes[k]; });
    const auto [mean, sd] = mean_and_std(p);
    const CycleStats cyc = analyse_cycles(ts, p, CycleAmplitude::std);
    const auto finite = [&](double v) {
      return cyc.ok && std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    };
    list.push_back({{"column", "p_probe_" + std::to_string(k + 1)},
                    {"point_m", {probes_[k].x, probes_[k].y}},
                    {"mean_pa", mean},
                    {"std_pa", sd},
                    {"peak_hz", peak_hz(spectra[k])},
                    {"spectrum", to_json(spectra[k])},
                    {"peak_period_s", finite(cyc.dominant_period)},
                    {"dominant_period_s", finite(cyc.regular ? cyc.dominant_period : NAN)},
                    {"cycle", cyc.ok ? cyc.verdict : "no regular cycle: record too short"},
                    {"peak_prominence", finite(cyc.peak_prominence)},
                    {"peak_amplitude_pa", finite(cyc.amplitude)},
                    {"peak_amplitude_share", finite(cyc.amplitude_share)}});
  }
  return list;
}

namespace {
// 06: the rows carry the bed top and the probes (each row saved with its probes' values).
constexpr const char* kRecorderTag = "FLBREC06";
static_assert(std::is_trivially_copyable_v<TimeseriesValues>);
static_assert(std::is_trivially_copyable_v<EnergyBudget> &&
              std::is_trivially_copyable_v<EnergyLedger>);
}  // namespace

template <class Archive>
void RunRecorder::fields(Archive& a) {
  a(first_step_, last_step_, row_every_, startup_, bed_, has_gas_, energy_start_, ledger_start_,
    rows_, pending_);
  a(max_overlap_, max_overlap_after_, ke_peak_, dp_sum_, dp_sq_, dp_max_, dp_max_time_,
    dp_samples_);
  a(last_gas_steps_, gas_steps_, simple_sum_, pressure_sum_, not_converged_, split_gas_steps_,
    simple_max_, residual_max_, cfl_max_, third_law_max_, fluid_fx_sum_, fluid_fy_sum_,
    fluid_samples_, bed_height_sum_, bed_height_samples_);
}

void RunRecorder::save(BinarySink& out) const {
  out.tag(kRecorderTag);
  const_cast<RunRecorder*>(this)->fields(out);
  out(bounces_.has_value(), bubbles_.has_value());
  if (bounces_) bounces_->save(out);
  if (bubbles_) bubbles_->save(out);
}

void RunRecorder::restore(BinarySource& in) {
  in.tag(kRecorderTag, "run recorder");
  // The recorder must be built for the same run (scene and end step) as the saved one.
  const std::int64_t last_step = last_step_, row_every = row_every_;
  const bool bed = bed_, has_gas = has_gas_;
  fields(in);
  bool bounces = false, bubbles = false;
  in(bounces, bubbles);
  const auto probes_differ = [&](const TimeseriesRow& r) {
    return r.probes.size() != probes_.size();
  };
  if (last_step != last_step_ || row_every != row_every_ || bed != bed_ || has_gas != has_gas_ ||
      bounces != bounces_.has_value() || bubbles != bubbles_.has_value() ||
      std::any_of(rows_.begin(), rows_.end(), probes_differ))
    in.fail("inconsistent (recorded for another scene or end time)");
  if (bounces_) bounces_->restore(in);
  if (bubbles_) bubbles_->restore(in);
}

void RunRecorder::add_drop_summary(nlohmann::json& j) const {
  const auto& e = bounces_->restitutions();
  const auto apex = bounces_->apex_heights();
  j["restitution"] = e.empty() ? nlohmann::json(nullptr) : nlohmann::json(e.front());
  j["rebound_height_ratio"] =
      apex.empty() ? nlohmann::json(nullptr) : nlohmann::json(apex.front() / bounces_->drop_height());
  j["drop_height_m"] = bounces_->drop_height();
  j["bounce_restitutions"] = e;
  j["bounce_heights_m"] = apex;
}

}  // namespace fluidbed
