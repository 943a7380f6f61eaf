#pragma once
// fluidbed study NAME [--out DIR] [--size tiny|full] [--jobs N] [--resume [DIR]] [--seeds N]
// | fluidbed study sensitivity --scene SCENE --vary KEY=V1,V2 [--vary ...] [--set KEY=V]
//   [--until T] [--seeds N] [--out DIR] [--resume] | fluidbed study --list
#include <string>
#include <vector>

namespace fluidbed::app {

struct StudyArgs {
  std::string name;
  std::string out;            // default out/study-NAME
  std::string size = "full";  // full | tiny
  bool quick = false;         // the same as --size tiny
  bool list = false;
  int jobs = 0;               // points at once; 0: one per core
  std::string resume;         // finish the study in this folder (its study.json)
  bool resume_out = false;    // --resume without a folder: the --out folder's
  // Over several packings (run/ensemble.hpp: "N" or "3,7,11"): each a whole study in
  // DIR/seeds/S/, the ensemble in DIR/ensemble.csv and DIR/summary.md; empty: one packing.
  std::string seeds;
  // `study sensitivity`: the scene, its --set, the --vary texts and --until (s; 0: the scene's).
  std::string scene;
  std::vector<std::string> overrides, vary;
  double until = 0.0;
};

int study_command(const StudyArgs& a);

}  // namespace fluidbed::app
