#include "run/umf_estimate.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/roots.hpp"
#include "core/steps.hpp"
#include "run/packed_bed.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {
namespace {

constexpr double kSteadyTime = 0.03;  // s of inflow: hundreds of the gas's response times

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

UmfEstimate estimate_umf(const Settings& scene,
                         const std::function<void(const std::string&)>& notify) {
  namespace fs = std::filesystem;
  const Settings fixed = fixed_bed_settings(scene, notify);
  UmfEstimate e;
  e.wen_yu = wen_yu_umf(scene.particles.diameter, scene.particles.density, scene.gas.density,
                        scene.gas.viscosity, scene.physics.gravity);
  if (!(e.wen_yu > 0.0))
    throw InputError("the particles are no heavier than the gas: no minimum fluidization");
  // Everything that decides the answer: the fixed bed's settings and its packed state (named by
  // the hash of its own settings).
  const std::string key = "umf fixed-bed balance v1\n" + to_toml(fixed) + "\nstate " +
                          fs::path(fixed.packed_state).filename().string() + "\n";
  Fnv1a h;
  h.bytes(key.data(), key.size());
  char name[64];
  std::snprintf(name, sizeof name, "umf-%016llx.txt", static_cast<unsigned long long>(h.digest()));
  e.cache_file = (fs::path(cache_dir()) / name).string();
  if (std::ifstream in(e.cache_file); in) {
    std::string word;
    double v = 0.0;
    if (in >> word >> v && word == "umf_m_s" && v > 0.0 && std::isfinite(v)) {
      e.umf = v;
      e.from_cache = true;
      return e;
    }
  }
  if (notify)
    notify(
        "measuring this scene's minimum fluidization velocity (fixed-bed force balance); "
        "cached as " +
        e.cache_file);
  std::map<double, double> seen;  // the bracket's ends are asked for again by false_position
  auto f = [&](double u) {
    if (auto it = seen.find(u); it != seen.end()) return it->second;
    ++e.evaluations;
    return seen[u] = fixed_bed_lift(fixed, u) - 1.0;
  };
  double lo = 0.5 * e.wen_yu, hi = 1.5 * e.wen_yu;
  double flo = f(lo), fhi = f(hi);
  for (int k = 0; k < 6 && flo > 0.0; ++k) flo = f(lo *= 0.5);
  for (int k = 0; k < 6 && fhi < 0.0; ++k) fhi = f(hi *= 1.5);
  if (!(flo < 0.0 && fhi > 0.0))
    throw SimulationFailure("the fixed bed's fluid force did not cross its weight between " +
                            std::to_string(lo) + " and " + std::to_string(hi) + " m/s");
  const RootBracket b = false_position(f, lo, hi, 8, 2e-3 * e.wen_yu);
  e.umf = b.secant_root();
  std::error_code ec;
  fs::create_directories(cache_dir(), ec);
  write_file_atomically(e.cache_file, [&](std::ofstream& out) {
    char line[128];
    std::snprintf(line, sizeof line, "umf_m_s %.6f\n", e.umf);
    out << line << "# " << UmfEstimate::kMethod << "\n";
  });
  return e;
}

}  // namespace fluidbed
