#include "run/packed_bed.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/steps.hpp"
#include "scene/scene_loader.hpp"
#include "sim/placement.hpp"
#include "sim/simulation.hpp"

namespace fluidbed {

Settings packing_settings_for(const Settings& bed) {
  Settings p = bed;
  p.scene = SceneInfo{};
  p.scene.name = "packing";
  p.scene.kind = SceneKind::Packing;
  p.particles.placement = Placement::Lattice;
  p.particles.state_file.clear();
  p.particles.frozen = false;
  p.inlet.kind = InletKind::None;
  p.inlet.superficial_velocity = 0.0;
  p.inlet.distributor_resistance = 0.0;  // no gas crosses the floor: the bed's own packing serves
  p.time.end = bed.particles.packing_time;
  p.diagnostics = DiagnosticsSettings{};
  p.diagnostics.overlap_limit = bed.diagnostics.overlap_limit;
  // The packing's own contact values, where the scene gives them (consumed here: the packing
  // run's settings hold them as its contact values).
  if (bed.particles.packing_friction) p.contact.friction = *bed.particles.packing_friction;
  if (bed.particles.packing_rolling_friction)
    p.contact.rolling_friction = *bed.particles.packing_rolling_friction;
  p.particles.packing_friction.reset();
  p.particles.packing_rolling_friction.reset();
  return p;
}

std::string cache_dir() {
  namespace fs = std::filesystem;
  if (const char* d = std::getenv("FLUIDBED_CACHE"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "fluidbed").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "fluidbed").string();
  return ".fluidbed-cache";
}

std::string packed_bed_state(const Settings& bed,
                             const std::function<void(const std::string&)>& notify) {
  namespace fs = std::filesystem;
  if (!bed.particles.packing_scene.empty()) {
    // Another scene packs the bed: its own packing, cached under its own settings.
    Settings other = load_scene(scene_path(bed, bed.particles.packing_scene));
    other.threads = bed.threads;
    if (bed.packing_seed) other.particles.seed = *bed.packing_seed;  // an ensemble's member
    if (other.particles.count != bed.particles.count ||
        other.particles.diameter != bed.particles.diameter)
      throw InputError("particles.packing_scene " + bed.particles.packing_scene +
                       " packs different particles (count or diameter) than this scene");
    other.particles.packing_scene.clear();
    other.particles.packing_time = bed.particles.packing_time;
    return packed_bed_state(other, notify);
  }
  const Settings packing = packing_settings_for(bed);
  // The key is every setting of the packing run, so a changed particle or contact value packs anew.
  // The model version goes in too: a change to the physics code that moves results bumps it.
  const std::string text = "model version 3\n" + to_toml(packing);
  Fnv1a h;
  h.bytes(text.data(), text.size());
  char name[64];
  std::snprintf(name, sizeof name, "packed-%016llx.state", static_cast<unsigned long long>(h.digest()));
  const fs::path dir = cache_dir();
  const fs::path path = dir / name;
  if (fs::exists(path)) return path.string();

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("cannot create the cache folder " + dir.string() + ": " + ec.message());
  if (notify)
    notify("packing the bed first (" + std::to_string(packing.particles.count) + " particles, " +
           std::to_string(packing.time.end) + " s); cached as " + path.string());
  Simulation sim(packing);
  const auto steps = steps_for(packing.time.end, packing.time.dt);
  while (sim.steps() < steps) sim.step();
  sim.save_state(path.string());
  return path.string();
}

void prepare_packed_bed(Settings& bed, const std::function<void(const std::string&)>& notify) {
  if (bed.particles.placement == Placement::Packed && bed.packed_state.empty())
    bed.packed_state = packed_bed_state(bed, notify);
}

}  // namespace fluidbed
