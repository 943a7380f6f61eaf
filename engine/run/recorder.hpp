#pragma once
// What a run records while it steps: one timeseries row per output interval and the running
// sums behind summary.json (the output contract of the architecture: summary keys and
// timeseries columns). The run loop (run/run_loop.hpp) steps the simulation and hands every step to
// the recorder; the recorder only reads the simulation.
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "analysis/bounce_tracker.hpp"
#include "analysis/energy_budget.hpp"
#include "analysis/spectrum.hpp"
#include "core/binary_io.hpp"
#include "run/bubble_recorder.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {

// The columns every run has: plain bytes, saved in a checkpoint as they are.
struct TimeseriesValues {
  double t = 0.0;                       // s
  double dp = 0.0;                      // Pa
  double max_overlap_ratio = 0.0;       // largest over the interval since the previous row
  double max_wall_overlap_ratio = 0.0;  // idem
  double kinetic_energy = 0.0;          // J
  int pair_contacts = 0;
  int wall_contacts = 0;
  // Gas (zeros without gas): the last gas step's SIMPLE iterations and mass residual, the
  // largest CFL number over the interval, the total fluid force on the particles (N).
  int simple_iterations = 0;
  double mass_residual = 0.0;
  double max_cfl = 0.0;
  double fluid_force_y = 0.0;
  // The particles' energy budget since the run's start (analysis/energy_budget.hpp).
  EnergyBudget energy;
  // With the bubble analysis (run --bubbles): bubbles in the latest frame, and the regime of
  // the frames of the trailing BubbleRecorder::kRegimeWindow.
  int bubbles = 0;
  Regime regime = Regime::fixed;
  // m: the bed's height at the row (analysis/packing_metrics.hpp: the mean over 1 cm columns
  // of the highest centre in each).
  double bed_height = 0.0;
  // m: the highest sphere centre at the row (analysis/packing_metrics.hpp: bed_top).
  double bed_top = 0.0;
};

// One row of timeseries.csv: the columns every run has and one per pressure probe.
struct TimeseriesRow : TimeseriesValues {
  // Pa, each probe of diagnostics.probes in order: the gas pressure at its point minus the mean
  // over the top row of cells (analysis/pressure_probe.hpp). Empty without probes.
  std::vector<double> probes;

  template <class Archive>
  void fields(Archive& a) {
    a(static_cast<TimeseriesValues&>(*this), probes);
  }
};

class RunRecorder {
 public:
  // Starts recording `sim` as it is now; the run ends at step `last_step`. With `bubbles`,
  // the bubble analysis runs beside it (its first frame now).
  RunRecorder(const Simulation& sim, std::int64_t last_step, bool bubbles = false);

  // After every step. Returns true when the step ended with a gas step.
  bool after_step(const Simulation& sim);

  const std::vector<TimeseriesRow>& rows() const { return rows_; }
  std::vector<TimeseriesRow> take_rows() { return std::move(rows_); }
  // summary.json of the run so far; wall: seconds of wall time the steps took.
  nlohmann::json summary(const Simulation& sim, double wall) const;
  // Welch's spectrum of dp after start-up (sampled at the rows; not ok without gas).
  PowerSpectrum dp_spectrum() const;
  // The same of each probe's pressure, in the order of diagnostics.probes.
  std::vector<PowerSpectrum> probe_spectra() const;
  // The probes' points (diagnostics.probes): one timeseries column each.
  const std::vector<ProbePoint>& probes() const { return probes_; }
  // The bubble analysis (null without --bubbles).
  const BubbleRecorder* bubbles() const { return bubbles_ ? &*bubbles_ : nullptr; }
  BubbleRecorder* bubbles() { return bubbles_ ? &*bubbles_ : nullptr; }

  // Its state as bytes and back: a run's checkpoint (run/checkpoint.hpp). restore expects a
  // recorder built for the same run (scene and end step) on the checkpoint's simulation and
  // refuses one that is not; the bubble analysis is saved with it.
  void save(BinarySink& out) const;
  void restore(BinarySource& in);

 private:
  template <class Archive>
  void fields(Archive& a);
  void gas_step_done(const CouplingDiagnostics& c);
  void write_row(const Simulation& sim);
  void add_gas_summary(const Simulation& sim, nlohmann::json& j) const;
  void add_drop_summary(nlohmann::json& j) const;
  void add_bed_top_summary(nlohmann::json& j) const;
  nlohmann::json probes_summary() const;
  // A column's values over the rows after start-up, and their times.
  template <class Column>
  std::vector<double> after_startup(Column&& column) const;
  std::vector<double> times_after_startup() const;
  // Welch's spectrum of a column after start-up (not ok for fewer than 8 rows).
  PowerSpectrum spectrum_after_startup(const std::vector<double>& series) const;

  std::int64_t first_step_ = 0, last_step_ = 0, row_every_ = 1;
  double startup_ = 0.0;  // s, averaging_start: where "after start-up" begins
  bool bed_ = false;      // scene.kind = SceneKind::Bed: the bed height is sampled at every row
  std::optional<BounceTracker> bounces_;
  std::optional<BubbleRecorder> bubbles_;
  bool has_gas_ = false;
  std::vector<ProbePoint> probes_;  // diagnostics.probes (the scene's, not saved)
  EnergyBudget energy_start_;      // the state's energy when recording began
  EnergyLedger ledger_start_;      // and the solver's ledger then
  std::vector<TimeseriesRow> rows_;
  TimeseriesRow pending_;

  double max_overlap_ = 0.0, max_overlap_after_ = 0.0, ke_peak_ = 0.0;
  double dp_sum_ = 0.0, dp_sq_ = 0.0, dp_max_ = -INFINITY, dp_max_time_ = 0.0;
  std::int64_t dp_samples_ = 0;
  // Gas solver and coupling statistics.
  int last_gas_steps_ = 0;
  std::int64_t gas_steps_ = 0, simple_sum_ = 0, pressure_sum_ = 0, not_converged_ = 0;
  std::int64_t split_gas_steps_ = 0;  // taken again as sub-steps (GasSolver::step)
  int simple_max_ = 0;
  double residual_max_ = 0.0, cfl_max_ = 0.0, third_law_max_ = 0.0;
  double fluid_fx_sum_ = 0.0, fluid_fy_sum_ = 0.0;
  std::int64_t fluid_samples_ = 0;
  double bed_height_sum_ = 0.0;  // m, summed over the rows after start-up (beds)
  std::int64_t bed_height_samples_ = 0;
};

}  // namespace fluidbed
