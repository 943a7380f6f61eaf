#include "run/umf_estimate.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>

#include <unistd.h>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/roots.hpp"
#include "core/steps.hpp"
#include "core/text_format.hpp"
#include "run/packed_bed.hpp"
#include "run/velocity_sweep.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {
namespace {

constexpr double kSteadyTime = 0.03;  // s of inflow: hundreds of the gas's response times
constexpr double kRunTime = 2.0, kAveraging = 1.0;  // s: as the teaching study's branch
}  // namespace

Settings fixed_bed_settings(const Settings& scene,
                            const std::function<void(const std::string&)>& notify) {
  if (!scene.gas.enabled)
    throw InputError("the scene has no gas: it has no minimum fluidization velocity");
  Settings s = scene;
  s.packed_state = packed_bed_state(scene, notify);
  s.particles.placement = Placement::Packed;
  s.particles.frozen = true;
  s.inlet.kind = InletKind::Uniform;
  s.inlet.superficial_velocity = 0.0;
  s.scene = SceneInfo{};
  s.scene.name = "fixed_bed";
  s.diagnostics = DiagnosticsSettings{};
  s.time.end = kSteadyTime;
  return s;
}

double fixed_bed_lift(const Settings& fixed, double u) {
  Settings s = fixed;
  s.inlet.superficial_velocity = u;
  Simulation sim(s);
  const std::int64_t steps = steps_for(kSteadyTime, s.time.dt);
  while (sim.steps() < steps) sim.step();
  const Particles& p = sim.dem().particles();
  const double force = std::accumulate(p.ext_fy.begin(), p.ext_fy.end(), 0.0);
  const double weight = std::accumulate(p.mass.begin(), p.mass.end(), 0.0) * s.physics.gravity;
  return force / weight;
}

double force_balance_umf(const Settings& scene, double wen_yu, int& runs,
                         const std::function<void(const std::string&)>& notify) {
  const Settings fixed = fixed_bed_settings(scene, notify);
  std::map<double, double> seen;  // the bracket's ends are asked for again by false_position
  auto f = [&](double u) {
    if (auto it = seen.find(u); it != seen.end()) return it->second;
    ++runs;
    return seen[u] = fixed_bed_lift(fixed, u) - 1.0;
  };
  double lo = 0.5 * wen_yu, hi = 1.5 * wen_yu;
  double flo = f(lo), fhi = f(hi);
  for (int k = 0; k < 6 && flo > 0.0; ++k) flo = f(lo *= 0.5);
  for (int k = 0; k < 6 && fhi < 0.0; ++k) fhi = f(hi *= 1.5);
  if (!(flo < 0.0 && fhi > 0.0))
    throw SimulationFailure("the fixed bed's fluid force did not cross its weight between " +
                            std::to_string(lo) + " and " + std::to_string(hi) + " m/s");
  return false_position(f, lo, hi, 8, 2e-3 * wen_yu).secant_root();
}

namespace {

// The scene as its U_mf sees it: what names it, its velocity, its end and its outputs do not
// decide U_mf (the sweep sets each run's velocity and length).
Settings umf_scene(const Settings& scene) {
  Settings s = scene;
  s.scene = SceneInfo{};
  s.scene.name = "umf";
  s.inlet.superficial_velocity = 0.0;
  s.time.end = 0.0;
  s.diagnostics.save_state.clear();
  s.diagnostics.probes.clear();
  s.threads = 1;  // the key's: results are the same bits for any thread count
  return s;
}

}  // namespace

bool read_umf_answer(const std::string& file, UmfEstimate& e) {
  std::ifstream in(file);
  if (!in) return false;
  std::string word;
  double v = 0.0;
  if (!(in >> word >> v) || word != "umf_m_s" || !(v > 0.0) || !std::isfinite(v)) return false;
  std::string how;
  if (!(in >> word >> how) || word != "method") return false;
  UmfEstimate r = e;
  r.umf = v;
  r.from_sweep = how == "decreasing_branch";
  while (in >> word && word == "point") {
    double u = 0.0, dp = 0.0;
    if (!(in >> u >> dp)) return false;
    r.u.push_back(u);
    r.dp.push_back(dp);
  }
  r.from_cache = true;
  r.cache_file = file;
  e = r;
  return true;
}

std::string UmfEstimate::method() const {
  if (scaled_from > 0.0)
    return format_number("the scene's own U_mf (%.3f m/s, its particles) scaled by ", scaled_from) +
           format_number("%.3f, the ratio of the fixed-bed force balances of the new particles' "
                         "packed bed and the scene's (not measured on a sweep)",
                         scale);
  return from_sweep
             ? "the decreasing branch of this scene's own sweep (" + std::to_string(u.size()) +
                   format_number(" velocities, %g s each), where the defluidized bed's line meets "
                                 "the plateau, ",
                                 kRunTime) +
                   "as `fluidbed sweep` finds it"
             : "fixed-bed force balance: the packed bed held still, uniform inflow, fluid force "
               "= weight (the sweep's way down gave none)";
}

std::string UmfEstimate::method_short() const {
  if (scaled_from > 0.0) return "estimated from the scene's for the new particles";
  return from_sweep ? "measured on the way down, as Fig. 6 is" : "the packed bed held still";
}

std::string umf_cache_name(const Settings& scene) {
  namespace fs = std::filesystem;
  const Settings s = umf_scene(scene);
  std::string start;
  if (s.particles.placement == Placement::Packed)
    start = fs::path(packed_bed_state(s)).filename().string();
  const std::string key = "umf decreasing branch v2\n" + to_toml(s) + "\nstart " + start + "\n";
  Fnv1a h;
  h.bytes(key.data(), key.size());
  char name[64];
  std::snprintf(name, sizeof name, "umf-%016llx.txt", static_cast<unsigned long long>(h.digest()));
  return name;
}

namespace {

// Wen and Yu's U_mf and the cache file's name into e (InputError for a bed without one); true
// when a measured answer was found there or in `shipped`.
bool known_answer(const Settings& scene, const std::string& shipped, UmfEstimate& e) {
  namespace fs = std::filesystem;
  if (!scene.gas.enabled)
    throw InputError("the scene has no gas: it has no minimum fluidization velocity");
  e.wen_yu = wen_yu_umf(scene.particles.diameter, scene.particles.density, scene.gas.density,
                        scene.gas.viscosity, scene.physics.gravity);
  if (!(e.wen_yu > 0.0))
    throw InputError("the particles are no heavier than the gas: no minimum fluidization");
  const std::string name = umf_cache_name(scene);
  e.cache_file = (fs::path(cache_dir()) / name).string();
  if (read_umf_answer(e.cache_file, e)) return true;
  return !shipped.empty() && read_umf_answer((fs::path(shipped) / name).string(), e);
}

}  // namespace

UmfEstimate estimate_umf(const Settings& scene,
                         const std::function<void(const std::string&)>& notify,
                         const std::string& shipped) {
  namespace fs = std::filesystem;
  UmfEstimate e;
  Settings s = umf_scene(scene);
  if (scene.gas.enabled) prepare_packed_bed(s, notify);  // said here, if it packs
  if (known_answer(scene, shipped, e)) return e;
  const std::string name = fs::path(e.cache_file).filename().string();

  const std::vector<double> velocities = decreasing_branch_velocities(scene);
  if (notify)
    notify("measuring this scene's minimum fluidization velocity from the way down of its sweep (" +
           std::to_string(velocities.size()) + " runs of " + std::to_string(int(kRunTime)) +
           " s, from " + format_number("%.2f", velocities.back()) + " m/s down; once: cached as " +
           e.cache_file + ")");
  // A folder of this process's own: two programs measuring the same scene at once each finish
  // their sweep (the answer file is written atomically).
  SweepOptions o = decreasing_branch_options(
      velocities, kRunTime, kAveraging,
      (fs::path(cache_dir()) / (fs::path(name).stem().string() + "-runs-" +
                                std::to_string(static_cast<long long>(::getpid()))))
          .string());
  o.log = [&](const std::string& line) {
    if (notify) notify("  " + line);
  };
  s.threads = scene.threads;  // the same bits on any number of threads: as fast as the scene may
  const SweepResult r = run_sweep(s, o);
  e.evaluations = static_cast<int>(velocities.size());
  std::error_code ec;
  fs::remove_all(o.out_dir, ec);
  if (r.umf.ok) {
    e.umf = r.umf.umf;
    e.from_sweep = true;
    for (const SweepPoint& p : way_down(r))
      if (p.ok) {
        e.u.push_back(p.u);
        e.dp.push_back(p.dp_mean);
      }
  } else {
    if (notify)
      notify("the way down gave no U_mf (" + r.umf.why +
             "): the fixed-bed force balance stands in");
    e.umf = force_balance_umf(scene, e.wen_yu, e.evaluations, notify);
  }
  fs::create_directories(cache_dir(), ec);
  write_file_atomically(e.cache_file, [&](std::ofstream& out) {
    out << format_number("umf_m_s %.6f\n", e.umf) << "method "
        << (e.from_sweep ? "decreasing_branch" : "force_balance") << "\n";
    for (std::size_t k = 0; k < e.u.size(); ++k)
      out << "point " << format_number("%.6g", e.u[k]) << " " << format_number("%.6g", e.dp[k])
          << "\n";
    out << "# " << e.method() << "\n";
  });
  return e;
}

UmfEstimate umf_for_particles(const UmfEstimate& measured, const Settings& scene,
                              const Settings& changed,
                              const std::function<void(const std::string&)>& notify,
                              const std::string& shipped) {
  UmfEstimate e;
  if (known_answer(changed, shipped, e)) return e;
  const double wen_yu_scene = wen_yu_umf(scene.particles.diameter, scene.particles.density,
                                         scene.gas.density, scene.gas.viscosity,
                                         scene.physics.gravity);
  const double balance_scene = force_balance_umf(scene, wen_yu_scene, e.evaluations, notify);
  const double balance_changed = force_balance_umf(changed, e.wen_yu, e.evaluations, notify);
  e.scale = balance_changed / balance_scene;
  e.scaled_from = measured.umf;
  e.umf = measured.umf * e.scale;
  e.cache_file.clear();  // an estimate, not kept: the cache holds measured answers
  return e;
}

}  // namespace fluidbed
