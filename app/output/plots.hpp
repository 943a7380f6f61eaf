#pragma once
// The figures the program draws itself (PNG, through chart.hpp): the sweep (Fig. 6), and from a
// single run dp against time (Fig. 8), the maximum overlap ratio against time (Fig. 15) and the
// trajectories of tracked particles (Figs 12-13).
#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "core/binary_io.hpp"
#include "run/run_loop.hpp"
#include "run/velocity_sweep.hpp"
#include "sim/simulation.hpp"

namespace fluidbed::app {

// Positions of one tracked particle at each recorded time.
struct Trajectory {
  int id = 0;
  std::vector<double> t, x, y;  // s, m, m

  template <class Archive>
  void fields(Archive& a) {
    a(id, t, x, y);
  }
};

// The particles nearest to the given points (m) at the start of a run (their ids).
std::vector<int> nearest_particles(const DemSolver& dem,
                                   const std::vector<std::pair<double, double>>& at);
// The default tracked particles: two starting in the jet region (the paper's Figs 12-13).
std::vector<std::pair<double, double>> jet_region_points(double width);

// Records tracked particles' positions every `interval` seconds of simulated time.
class TrajectoryRecorder {
 public:
  TrajectoryRecorder(const std::vector<int>& ids, double interval, double dt);
  void observe(const Simulation& sim);
  const std::vector<Trajectory>& tracks() const { return tracks_; }
  // The tracks so far (ids included) as bytes and back, for a run's checkpoint.
  void save(BinarySink& out) const;
  // InputError (naming the file) unless the tracks are as many as this recorder's and their ids
  // below `particles`.
  void restore(BinarySource& in, std::size_t particles);

 private:
  std::vector<Trajectory> tracks_;
  std::int64_t every_;
};

// FOLDER/tracks.bin, a run's checkpoint's copy of its tracked particles (run/checkpoint.hpp's
// add_files): written whole (InputError when it cannot be), and read back into a recorder made
// for the same run (InputError naming the file when it does not fit).
void save_tracks(const std::string& folder, const TrajectoryRecorder& r);
void restore_tracks(const std::string& folder, TrajectoryRecorder& r, std::size_t particles);

void plot_sweep(const std::string& path, const SweepResult& r, const std::string& scene);

// An ensemble of sweeps (`sweep --seeds`): each seed's two branches faint, the mean over the
// seeds at each velocity bold, U_mf's ensemble mean as a line and mean +- one standard deviation
// as the band's edges (no band when std is null: one seed).
void plot_sweep_ensemble(const std::string& path, const std::vector<SweepResult>& members,
                         const nlohmann::json& umf_stats, const std::string& scene);

// One seed's dp against time in an ensemble (`run --seeds --plots`).
struct SeedTrace {
  std::uint64_t seed = 0;
  std::vector<double> t, dp;  // s, Pa
};
// dp against time of every seed overlaid, the bed weight per area dashed.
void plot_dp_ensemble(const std::string& path, const std::vector<SeedTrace>& traces,
                      double bed_weight_per_area, const std::string& scene);

// Writes DIR/dp.png (when the run has gas), DIR/overlap.png, DIR/dp_spectrum.png (when dp has a
// spectrum), DIR/bubbles.png and DIR/mixing.png (with the bubble analysis) and, for the
// trajectories, DIR/trajectory.png (path in the bed, x and y against time). Returns the files
// written.
std::vector<std::string> plot_run(const std::string& dir, const RunResult& r,
                                  const std::vector<Trajectory>& tracks, double width,
                                  double height, bool has_gas);

}  // namespace fluidbed::app
