#pragma once
// `fluidbed view [SCENE] [--set K=V]... [--script FILE | --lesson NAME] [--out DIR]`: the bed live
// in a window with a control panel (docs/teaching.md). Without a display it says so in one
// line and runs the scene headlessly with the same settings into frames (and, for a lesson, a
// video with its captions) instead.
#include <string>
#include <vector>

#include "cli/commands.hpp"

namespace fluidbed::app {

struct ViewArgs {
  // scene (empty: assets/scenes/teaching.toml, or the lesson's), --set, --threads; --until:
  // headless only, the simulated time to reach (< 0: the scene's time.end).
  RunArgs run_like;
  std::string script;  // a view script (view/script.hpp); empty: interactive
  std::string lesson;  // a lesson of assets/lessons (its NAME.txt), run as a script
  bool list_lessons = false;
  bool umf_only = false;  // --umf: print the scene's U_mf (measured once, cached) and exit
  std::string beside;    // a second scene beside the first (the window's; --set applies to both)
  bool present = false;  // the window opens in the presenter mode (headless frames: no change)
  std::string out;                    // screenshots, recordings, headless frames; empty: out/view
  OutputArgs output;                  // the look (colour, arrows, ...); frame_size: the window
  double max_fps = 30.0;              // the window's drawing rate at most (0: no cap)
  bool frame_interval_given = false;  // --frame-interval on the command line (lessons: 0.02 s)
  // The window's size when --frame-size is not given (the frames' default too, so `view --help`
  // says what opens).
  static constexpr const char* kWindowSize = "1280x720";
  ViewArgs() { output.frame_size = kWindowSize; }
};

int view_command(const ViewArgs& a);

// The lessons shipped in assets/lessons: NAME and its title (the file's first comment line).
std::vector<std::pair<std::string, std::string>> list_lessons();

}  // namespace fluidbed::app
