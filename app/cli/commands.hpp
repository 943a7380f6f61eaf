#pragma once
// The verbs of the command line. Each returns the process exit status; input errors and
// simulation failures propagate as exceptions and are turned into statuses 2 and 3 by main.
#include <string>
#include <vector>

#include "output/output_args.hpp"
#include "render/asset_dir.hpp"

namespace fluidbed::app {

struct RunArgs {
  std::string scene;
  std::vector<std::string> overrides;
  double until = -1.0;  // s, < 0: the scene's time.end
  std::string out;      // output folder; empty: out/<scene file name>
  int threads = 1;      // threads inside a step; 0: one per core
  OutputArgs output;    // run only
  bool plots = false;   // run: dp.png, overlap.png, trajectory.png
  std::string track;    // run --plots: particle ids "12,345"; empty: two from the jet region
  bool bubbles = false; // run: the bubble analysis (bubbles.csv, mixing.csv, summary `bubbles`)
  // run: wall seconds between checkpoints (DIR/checkpoint/); < 0: every 60 s once the run is
  // expected to take over 2 minutes; 0: none but the one an interrupt writes.
  double checkpoint_every = -1.0;
  std::string resume;          // run --resume DIR: finish the run whose checkpoint DIR holds
  bool threads_given = false;  // --threads was on the command line
  // run: the output options on the command line, by their names in a checkpoint's options.json
  // ("frame_size", "plots", ...): a resumed run refuses one that differs from the run's.
  std::vector<std::string> outputs_given;
  int repeat = 1;       // bench: runs of the same work (median, min and max reported)
  // run --seeds: an ensemble over packings (run/ensemble.hpp: "N" or "3,7,11"); empty: one run.
  std::string seeds;
};

// Calls f(option, key, member) for each output option of `run`: its command-line name, its
// name in a checkpoint's options.json and the member it sets (bool, double or string).
template <class F>
void visit_output_options(RunArgs& a, F&& f) {
  OutputArgs& o = a.output;
  f("--frames", "frames", o.frames);
  f("--video", "video", o.video);
  f("--vtk", "vtk", o.vtk);
  f("--montage", "montage", o.montage);
  f("--frame-interval", "frame_interval", o.frame_interval);
  f("--frame-size", "frame_size", o.frame_size);
  f("--colour", "colour", o.colour);
  f("--colour-range", "colour_range", o.colour_range);
  f("--gas-arrows", "gas_arrows", o.gas_arrows);
  f("--gas-arrow-colour", "gas_arrow_colour", o.gas_arrow_colour);
  f("--particle-arrows", "particle_arrows", o.particle_arrows);
  f("--porosity-background", "porosity_background", o.porosity_background);
  f("--bubble-outlines", "bubble_outlines", o.bubble_outlines);
  f("--dark", "dark", o.dark);
  f("--close-up", "close_up", o.close_up);
  f("--video-fps", "video_fps", o.video_fps);
  f("--gl-backend", "gl_backend", o.gl_backend);
  f("--plots", "plots", a.plots);
  f("--track", "track", a.track);
  f("--bubbles", "bubbles", a.bubbles);
}

struct SweepArgs {
  std::string scene;
  std::vector<std::string> overrides;
  std::string velocities;        // "0.5,1.0,..." (m/s); empty: the default 23
  double run_time = 1.5;         // s per velocity
  double averaging_start = 0.5;  // s into each run
  int threads = 2;               // runs side by side
  std::string out;
  std::string seeds;  // sweep --seeds: one sweep per packing (run/ensemble.hpp); empty: one
  std::string resume;          // sweep --resume DIR: finish the sweep in DIR (cli/sweep.cpp)
  bool threads_given = false;  // --threads on the command line
  bool options_given = false;  // a scene, --set, --velocities, --run-time, --averaging-start or --seeds
};

struct ReproduceArgs {
  std::string out;
  std::vector<std::string> overrides;  // applied to every scene (e.g. a smaller bed)
  bool quick = false;  // every figure at lower fidelity, in minutes
  int threads = 1;
  std::string seeds;  // packings (run/ensemble.hpp); empty: 3, with --quick 1
  std::string resume;          // reproduce --resume DIR: finish the report in DIR
  bool options_given = false;  // --quick, --seeds or --set on the command line
  bool threads_given = false;  // --threads on the command line
};

// How a command was started, as the identity file it resumes from keeps it (`run`: the
// checkpoint's options.json and `run --seeds`' ensemble.json, with the output options under
// "outputs"; `sweep`: sweep.json's "command"; `reproduce`: reproduce.json): f(key, member) for each
// field, one list for writing and reading (core/json_fields.hpp).
template <class Args, class F>
void run_identity_fields(Args& a, F&& f) {
  f("scene", a.scene);
  f("overrides", a.overrides);
  f("until_s", a.until);
  f("threads", a.threads);
  f("checkpoint_every_s", a.checkpoint_every);
}
template <class Args, class F>
void sweep_identity_fields(Args& a, F&& f) {
  f("scene", a.scene);
  f("overrides", a.overrides);
  f("velocities", a.velocities);
  f("run_time_s", a.run_time);
  f("averaging_start_s", a.averaging_start);
  f("threads", a.threads);
  f("seeds", a.seeds);
}
template <class Args, class F>
void reproduce_identity_fields(Args& a, F&& f) {
  f("quick", a.quick);
  f("seeds", a.seeds);
  f("overrides", a.overrides);
  f("threads", a.threads);
}

struct CheckArgs {
  std::string scene;
  std::vector<std::string> overrides;
};

int run_command(const RunArgs& a);

int check_command(const CheckArgs& a);
int bench_command(const RunArgs& a);
int sweep_command(const SweepArgs& a);
int reproduce_command(const ReproduceArgs& a);

// The shipped assets folder (scenes, fonts): $FLUIDBED_ASSETS, else an installed copy's share
// folder, else the source tree's (render/asset_dir.hpp).
using render::asset_dir;

}  // namespace fluidbed::app
