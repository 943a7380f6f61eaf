#pragma once
// A scene's own minimum fluidization velocity, measured from its model (the viewer's presets
// and slider scale): the velocity at which the fluid force the scene's model puts on its packed
// bed, held fixed with a uniform inflow, equals the bed's weight (the fixed-bed force balance of
// the test CoupledBed.MinimumFluidizationFromTheModel). Each evaluation is 0.03 s of steady gas
// through the frozen bed; false position between brackets around Wen and Yu's estimate finds
// the root in about eight. The answer is cached beside the packed bed (run/packed_bed.hpp), by
// the hash of the settings that decide it, so a scene is measured once.
#include <functional>
#include <string>

#include "scene/settings.hpp"

namespace fluidbed {

struct UmfEstimate {
  double umf = 0.0;     // m/s
  double wen_yu = 0.0;  // m/s, Wen and Yu's correlation for the same particles and gas
  int evaluations = 0;  // fixed-bed runs (0 when read from the cache)
  bool from_cache = false;
  std::string cache_file;
  // How it was measured, one line for a panel.
  static constexpr const char* kMethod =
      "fixed-bed force balance: the packed bed held still, uniform inflow, fluid force = weight";
};

// The fluid force on the frozen packed bed over its weight at superficial velocity u (m/s), after
// 0.03 s of uniform inflow. `fixed`: from fixed_bed_settings.
double fixed_bed_lift(const Settings& fixed, double u);
// The scene's packed bed held still with a uniform distributor (packing it first when needed).
Settings fixed_bed_settings(const Settings& scene,
                            const std::function<void(const std::string&)>& notify = {});

// Measured, or read from the cache. InputError for a scene without gas.
UmfEstimate estimate_umf(const Settings& scene,
                         const std::function<void(const std::string&)>& notify = {});

}  // namespace fluidbed
