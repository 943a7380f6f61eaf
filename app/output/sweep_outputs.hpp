#pragma once
// What a velocity sweep writes (run/velocity_sweep.hpp runs it): sweep.csv, summary.json with
// U_mf and sweep.png; and a sweep over several packings (`sweep --seeds`, reproduce's sweeps)
// through the ensemble driver (run/ensemble.hpp).
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run/velocity_sweep.hpp"
#include "scene/settings.hpp"

namespace fluidbed::app {

// sweep.csv, summary.json (with umf_m_s) and sweep.png in the sweep's output folder.
void write_sweep_outputs(const SweepResult& r, const SweepOptions& o, const std::string& scene);
// The sweep's summary.json as written by write_sweep_outputs.
nlohmann::json sweep_summary(const SweepResult& r, const SweepOptions& o, const std::string& scene);

struct SweepEnsemble {
  bool interrupted = false;               // a stop ended a member's sweep: resume the ensemble
  std::vector<SweepResult> members;       // in seed order
  std::vector<nlohmann::json> summaries;  // each member's summary.json, in seed order
  nlohmann::json summary;                 // DIR/summary.json
};

// One sweep per packing (`seeds`), one after another, each with its runs side by side, in
// base.out_dir/seeds/S/ (each sweep's usual files); base.out_dir/ensemble.json (its `identity`,
// run/ensemble.hpp), and once every sweep finished: the ensemble's summary.json (umf_m_s and
// every other number as {mean, std, min, max, n}), sweep.csv (the mean dp over the seeds at each
// velocity of each branch, with its spread) and sweep.png (each seed's branches faint, the means
// bold, U_mf's mean +- one standard deviation). `log(seed, line)` hears each member's lines. A
// refused resume (another scene or options) is refused before any folder is touched.
SweepEnsemble sweep_over_seeds(const Settings& scene, const std::vector<std::uint64_t>& seeds,
                               const SweepOptions& base, const nlohmann::json& identity,
                               const std::function<void(std::uint64_t, const std::string&)>& log);

}  // namespace fluidbed::app
