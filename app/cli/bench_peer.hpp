#pragma once
// fluidbed bench --peer liggghts: fluidbed against LIGGGHTS 3.8 (Debian's `liggghts`, one
// process) on the same work in one command. The scene (default: packing.toml) is exported as
// `fluidbed export --to liggghts` writes it (into OUT/liggghts/), run in LIGGGHTS, and run in
// fluidbed with the gas left out as the deck leaves it out (LIGGGHTS is DEM only); the same
// particle count, steps, dt and end time are checked from LIGGGHTS' own log. Both wall times
// (LIGGGHTS' "Loop time" and its whole process, setup included; fluidbed's step loop and its
// whole run), particle-steps per second and their ratio are printed and added to OUT/bench.json
// as its "peer" object.
#include <string>

#include "cli/commands.hpp"

namespace fluidbed::app {

// `peer` must be "liggghts". A missing binary is installed with apt-get when running as root;
// otherwise InputError says how to install it. A "packed" start is refused (the deck packs the
// bed first, fluidbed starts from its cache: not the same work). LIGGGHTS failing, or the work
// differing, throw SimulationFailure.
int bench_peer_command(const RunArgs& a, const std::string& peer);

}  // namespace fluidbed::app
