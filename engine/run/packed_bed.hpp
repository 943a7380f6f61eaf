#pragma once
// The packed bed every fluidization run starts from (the paper's section 3): this scene's
// particles on the random lattice start, falling with the gas at rest for packing_time. It is
// generated once per distinct set of settings and cached, so a sweep of 23 runs packs once.
#include <functional>
#include <string>

#include "scene/settings.hpp"

namespace fluidbed {

// The packing run that belongs to a bed scene: same domain, particles, contact law, integrator
// and gas, no inflow, lattice placement, time.end = particles.packing_time.
Settings packing_settings_for(const Settings& bed);

// Folder of cached packed beds: $FLUIDBED_CACHE, else $XDG_CACHE_HOME/fluidbed, else
// ~/.cache/fluidbed, else ./.fluidbed-cache.
std::string cache_dir();

// Path of the packed state for `bed`, running and caching the packing first when needed.
// `notify` (may be empty) hears one line when a packing is generated.
std::string packed_bed_state(const Settings& bed,
                             const std::function<void(const std::string&)>& notify = {});

// For placement = "packed": sets bed.packed_state (the cached packed bed, made first when
// needed) so that a Simulation can be built from `bed`. Any other placement: nothing to do.
void prepare_packed_bed(Settings& bed, const std::function<void(const std::string&)>& notify = {});

}  // namespace fluidbed
