#pragma once
// `fluidbed view` without a window: the scene run headlessly, its script (or lesson) carried out
// at its simulated times, pictures of what the window would show at every frame interval: the
// bed with the caption band, the regime over the bed, and beside it (beds with gas) the live
// Fig. 6 and dp against time. PNG frames into DIR/frames, and with --video or a lesson an MP4,
// DIR/video.mp4, at 25 frames per second.
#include <string>

#include "output/frames.hpp"
#include "run/umf_estimate.hpp"
#include "scene/settings.hpp"
#include "view/script.hpp"

namespace fluidbed::app {

struct HeadlessView {
  FrameOptions frames;  // size, interval, look, font (frames.frames / frames.video: outputs)
  std::string out;      // the folder
  double until = -1.0;  // s, --until (< 0: the script's quit, else the scene's end)
  UmfEstimate umf;      // the scene's measured U_mf (presets; umf 0: not measured)
  std::string umf_shipped;  // the folder of shipped U_mf answers (a change of the particles)
};

int view_headless(const Settings& scene, const ViewScript& script, const HeadlessView& o);

}  // namespace fluidbed::app
