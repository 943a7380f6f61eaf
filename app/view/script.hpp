#pragma once
// `fluidbed view SCENE --script FILE`: the viewer driven by a file, for tests and for demo videos
// made without hands. One command a line; `#` starts a comment. A line may begin with `at T`: the
// engine first runs to the step nearest simulated time T (s) and stops there, so the command acts
// at an exact moment. Lines run in order; when the last has run the viewer goes on as usual
// (running, unless the script paused it), or closes at `quit`.
//
//   at 0.05 velocity 1.8       superficial gas velocity (m/s) from the next gas step
//   velocity 1.2 umf           ... as a multiple of the scene's measured U_mf
//   preset NAME                a stage of Fig. 6: fixed, minimum, bubbling, slugging (view/presets)
//   ideal on|off               contact damping 0 and friction 0 (the paper's ideal case)
//   stiffness K | scene        contact stiffness (N/m), damping scaled to keep the restitution
//   particles D RHO | scene    spheres of diameter D (m) and density RHO (kg/m^3), the count
//                              kept: a packed bed of them at the velocity held (view/session.hpp)
//   settle S   average S       the live curve's settling time and averaging window (simulated s)
//   curve FILE.csv|FILE.png    save the live curve (Fig. 6 as the class built it)
//   caption "TEXT" | off       a line of text over the bed (window, screenshots, videos)
//   run | pause | step [N]     the run switch; N single steps (simulated time moves N dt)
//   reset                      back to the packed bed (the state at the start, exactly)
//   wait S                     let the bed run for S wall seconds (if running), then stop
//   colour MODE                the viewer's colour words (render/colour_by.hpp): speed, force,
//                              torque, overlap, mixing (the initial-height bands), depth
//   gas-arrows on|off   particle-arrows on|off   porosity on|off
//   bubbles on|off             outlines of the bubbles and jet cavities found ([bubbles])
//   track ID | track off       follow a particle and draw its path
//   zoom F                     zoom factor (1: the whole frame)
//   screenshot FILE.png        the window as shown (panel and bed)
//   record FILE.mp4|DIR        start recording the window (MP4, or PNG frames in DIR)
//   record stop
//   quit                       close the viewer, exit status 0
// A lesson (assets/lessons/) may begin with `scene NAME`: the scene it is written for (a file of
// assets/scenes/, or a path), used when the command line names none.
#include <string>
#include <vector>

namespace fluidbed::app {

struct ScriptLine {
  enum class Kind {
    velocity,
    ideal,
    run,
    pause,
    step,
    reset,
    wait,
    colour,
    gas_arrows,
    particle_arrows,
    porosity,
    bubbles,
    track,
    zoom,
    screenshot,
    record,
    record_stop,
    quit,
    caption,
    preset,
    stiffness,
    settle,
    average,
    curve,
    particles,
  };
  double at = -1.0;  // s of simulated time; < 0: right after the previous line
  Kind kind = Kind::quit;
  double number =
      0.0;           // velocity (m/s), step count, wait (s), track id (-1: off), zoom, on/off (1/0)
  double density = 0.0;  // particles: kg/m^3 (number: the diameter, m; 0 and 0: the scene's)
  std::string text;  // colour mode, file, caption, preset; velocity: "umf" (a multiple of U_mf)
  int line = 0;      // in the file, for messages
};

// A script with the scene it asks for (`scene NAME` on its first command line; empty: none).
struct ViewScript {
  std::vector<ScriptLine> lines;
  std::string scene;
  // Any line that needs the scene's measured U_mf (presets, `velocity F umf`).
  bool needs_umf() const;
};

// Parses script text; InputError "ORIGIN line N: ..." naming the problem.
ViewScript parse_view_script(const std::string& text, const std::string& origin);
// Reads and parses FILE; InputError when it cannot be read.
ViewScript load_view_script(const std::string& path);

}  // namespace fluidbed::app
