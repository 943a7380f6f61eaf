#pragma once
// The report of `fluidbed reproduce`: what its runs, sweeps and studies measured, beside the
// paper's figures (report.md). cli/reproduce.cpp runs them; this writes the words.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "run/velocity_sweep.hpp"
#include "studies/common.hpp"

namespace fluidbed::app {

// What the report is made from.
struct PaperRuns {
  std::vector<std::uint64_t> seeds;  // the packings, in order
  std::vector<nlohmann::json> paper,
      uniform;                            // the jetted and the uniform bed's summaries, per seed
  nlohmann::json ideal, ideal_geometric;  // the ideal case's two runs (the first seed)
  double paper_wall = 0.0;                // s, the first seed's paper run
  int paper_threads = 1;                  // threads inside its step
  std::vector<nlohmann::json> sweeps;     // each seed's sweep summary
  SweepResult first_sweep;                // the first seed's sweep
  double sweep_run_time = 0.0, sweep_averaging_start = 0.0;  // s
  std::vector<study::Report> studies;
  double paper_time = 0.0, uniform_time = 0.0, ideal_time = 0.0;  // s simulated
  double averaging = 0.0;                                         // s, averaging start of the runs
  // The second bed (van Wachem et al. 2001, its scene as shipped): one run per packing, none
  // with --quick.
  std::vector<std::uint64_t> second_bed_seeds;
  std::vector<nlohmann::json> second_bed;
};

// The second bed's section of report.md: van Wachem's bed over the packings `seeds` (each
// run's summary in `runs`), each figure per packing and as mean +- standard deviation beside the
// experiment's (Lethe's reference files), and whether the experiment's value lies within two
// standard deviations. No runs: the section says that --quick leaves the bed out and how to run it.
std::string second_bed_section(const std::vector<nlohmann::json>& runs,
                               const std::vector<std::uint64_t>& seeds);

// report.md: the table against the paper, the figures, the ideal case, the studies and the
// settings; `total_wall` the report's wall seconds.
std::string paper_report(const ReproduceArgs& a, const PaperRuns& r, double total_wall);

}  // namespace fluidbed::app
