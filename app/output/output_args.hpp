#pragma once
// What `run` is asked to draw and write besides its numbers: the options of its pictures and
// files at exact simulated times (`--frames --video --vtk --montage ...`, output/frames.hpp).
#include <string>

namespace fluidbed::app {

// Pictures and files of a run at exact simulated times (`run --frames --video --vtk --montage`,
// see output/frames.hpp and docs/pictures.md).
struct OutputArgs {
  bool frames = false, video = false, vtk = false;
  std::string montage;                  // "0.2,0.4,0.6" (s); empty: none
  double frame_interval = 0.04;         // s of simulated time (25 frames per simulated second)
  std::string frame_size = "1280x720";  // px
  std::string colour = "speed";         // speed, force, torque, overlap, height, depth, fixed
  std::string colour_range;             // "MIN,MAX" in the quantity's unit; empty: its default
  bool gas_arrows = true, gas_arrow_colour = false, particle_arrows = false;
  bool porosity_background = false, dark = false;
  bool bubble_outlines = false;  // the bubble analysis' outlines over the particles
  double close_up = 0.4;         // frames: magnified lower fraction of the bed (0: none)
  double video_fps = 25.0;
  std::string gl_backend = "osmesa";
};

}  // namespace fluidbed::app
