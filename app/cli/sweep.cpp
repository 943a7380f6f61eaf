// fluidbed sweep: the paper's Fig. 6, both branches, and U_mf from the decreasing one.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/json_fields.hpp"
#include "output/sweep_outputs.hpp"
#include "run/ensemble.hpp"
#include "run/velocity_sweep.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

namespace fluidbed::app {
namespace {

std::vector<double> parse_velocities(const std::string& list) {
  std::vector<double> v;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError("--velocities: \"" + item + "\" is not a number (expected e.g. 0.5,1.0,1.5)");
    }
  }
  return v;
}

// How the sweep was started, kept in DIR/sweep.json for `sweep --resume DIR`.
nlohmann::json sweep_command_json(SweepArgs a) {
  a.scene = std::filesystem::absolute(a.scene).lexically_normal().string();
  return fields_json(a, [](auto& r, auto&& f) { sweep_identity_fields(r, f); });
}

// `sweep --resume DIR`: the sweep's arguments from DIR/sweep.json; only --threads (which changes
// no result) may be given beside it.
SweepArgs resumed_sweep_args(const SweepArgs& given) {
  const std::string head = "cannot resume " + given.resume + ": ";
  check_resume_only(given.options_given, given.out, given.resume, "sweep",
                    "its scene and options from DIR/sweep.json");
  // A sweep over packings keeps how it was started in DIR/ensemble.json, a single one in
  // DIR/sweep.json.
  const nlohmann::json j = holds_ensemble(given.resume)
                               ? read_ensemble_identity(given.resume, "sweep --seeds", head)
                               : read_sweep_identity(given.resume);
  SweepArgs a = given;
  a.out = given.resume;
  try {
    fields_from_json(j.at("command"), a, [](auto& r, auto&& f) { sweep_identity_fields(r, f); });
    if (given.threads_given) a.threads = given.threads;
  } catch (const nlohmann::json::exception&) {
    throw InputError(head + "its sweep.json does not say how the sweep was started");
  }
  return a;
}

SweepOptions sweep_options(const SweepArgs& a) {
  SweepOptions o;
  if (!a.velocities.empty()) o.velocities = parse_velocities(a.velocities);
  o.run_time = a.run_time;
  o.averaging_start = a.averaging_start;
  o.threads = a.threads;
  o.out_dir = a.out.empty() ? "out/sweep" : a.out;
  o.log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  o.resume = !a.resume.empty();
  o.stop = [] { return InterruptGuard::received() != 0; };
  o.command = sweep_command_json(a);
  return o;
}

// `sweep --seeds`: one sweep per packing (output/sweep_outputs.hpp: sweep_over_seeds).
int sweep_ensemble(const SweepArgs& a) {
  Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  check_seeded_start(s);
  const std::vector<std::uint64_t> seeds = parse_seeds(a.seeds, lattice_seed(s));
  const SweepOptions base = sweep_options(a);
  const InterruptGuard interrupts;
  const SweepEnsemble e = sweep_over_seeds(
      s, seeds, base, {{"kind", "sweep --seeds"}, {"command", base.command}},
      [](std::uint64_t seed, const std::string& line) {
        std::printf("seed %llu: %s\n", static_cast<unsigned long long>(seed), line.c_str());
        std::fflush(stdout);
      });
  if (e.interrupted) {
    say_interrupted("fluidbed sweep --resume " + base.out_dir);
    return 130;
  }
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    const UmfFit& f = e.members[k].umf;
    if (f.ok)
      std::printf("seed %llu: U_mf = %.3f m/s\n", static_cast<unsigned long long>(seeds[k]), f.umf);
    else
      std::printf("seed %llu: U_mf not found: %s\n", static_cast<unsigned long long>(seeds[k]),
                  f.why.c_str());
  }
  const nlohmann::json& st = e.summary["ensemble"];
  if (st.contains("umf_m_s"))
    std::printf("U_mf (m/s) over %zu seeds: %s\n", seeds.size(),
                ensemble_line(st["umf_m_s"], "%.3f").c_str());
  else
    std::printf("U_mf not found in any seed's sweep\n");
  std::printf("wrote %s/summary.json, sweep.csv, sweep.png and seeds/S/\n", base.out_dir.c_str());
  return 0;
}

}  // namespace

int sweep_command(const SweepArgs& given) {
  SweepArgs a = given;
  if (!given.resume.empty())
    a = resumed_sweep_args(given);
  else if (a.scene.empty())
    throw InputError("sweep: give a scene file (fluidbed sweep SCENE.toml) or --resume DIR");
  if (!a.seeds.empty()) return sweep_ensemble(a);
  const Settings s = load_scene(a.scene, a.overrides);
  refuse_unsafe_scene(s);
  const SweepOptions o = sweep_options(a);
  check_sweep_resume(s, o);  // a refused resume leaves the folder as it was
  std::filesystem::create_directories(o.out_dir);
  std::filesystem::remove(std::filesystem::path(o.out_dir) / "summary.json");  // only a finished sweep has one
  const InterruptGuard interrupts;
  const SweepResult r = run_sweep(s, o);
  if (r.interrupted) {
    say_interrupted("fluidbed sweep --resume " + o.out_dir);
    return 130;
  }
  write_sweep_outputs(r, o, s.scene.name);
  if (r.umf.ok)
    std::printf("U_mf = %.3f m/s (plateau %.0f Pa; bed weight per area %.0f Pa)\n", r.umf.umf,
                r.umf.plateau, r.bed_weight_per_area);
  else
    std::printf("U_mf not found: %s\n", r.umf.why.c_str());
  std::printf("wrote %s/sweep.csv, sweep.png and summary.json (%.0f s)\n", o.out_dir.c_str(),
              r.wall_time);
  return 0;
}

}  // namespace fluidbed::app
