#pragma once
// `fluidbed view [SCENE] [--set K=V]... [--script FILE] [--out DIR]`: the bed live in a window
// with a control panel (README.md, "Viewer"). Without a display it says so in one line and writes
// headless frames with the same settings instead.
#include <string>
#include <vector>

#include "cli/commands.hpp"

namespace fluidbed::app {

struct ViewArgs {
  // scene (empty: assets/scenes/teaching.toml), --set, --threads; --until: headless only, the
  // simulated time to reach (< 0: the scene's time.end).
  RunArgs run_like;
  std::string script;  // a view script (view/script.hpp); empty: interactive
  std::string out;     // screenshots, recordings, headless frames; empty: out/view
  OutputArgs output;   // the look (colour, arrows, ...); frame_size: the window
  double max_fps = 30.0;  // the window's drawing rate at most (0: no cap)
  ViewArgs() { output.frame_size = "1360x800"; }
};

int view_command(const ViewArgs& a);

}  // namespace fluidbed::app
