#include "output/run_checkpoint.hpp"

namespace fluidbed::app {

void checkpoint_with_outputs(RunOptions& opt, const OutputCheckpoint& c, const Checkpoint* resumed) {
  opt.checkpoint = [c](const Simulation& x, const RunRecorder& rec, double wall) {
    write_checkpoint(c.dir, x, rec, wall, c.scene_toml, c.options, c.bubbles,
                     [&](const std::string& folder) {
                       if (c.pictures) c.pictures->checkpoint(folder);
                       if (c.tracks) save_tracks(folder, *c.tracks);
                     });
  };
  if (resumed) {
    opt.restore = [resumed](RunRecorder& rec) { restore_recorder(*resumed, rec); };
    opt.wall_before = resumed->wall;
  }
}

void remove_run_checkpoint(const std::string& dir) {
  remove_checkpoint(dir);
  remove_video_parts(dir);
}

void set_checkpoint_interval(RunOptions& opt, double every) {
  opt.checkpoint_interval = every < 0.0 ? 60.0 : every;
  opt.checkpoint_min_run = every < 0.0 ? 120.0 : 0.0;
}

}  // namespace fluidbed::app
