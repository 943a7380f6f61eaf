#pragma once
// fluidbed study NAME [--out DIR] [--size tiny|full] [--jobs N] [--resume DIR] [--seeds N]
// | fluidbed study --list
#include <string>

namespace fluidbed::app {

struct StudyArgs {
  std::string name;
  std::string out;            // default out/study-NAME
  std::string size = "full";  // full | tiny
  bool quick = false;         // the same as --size tiny
  bool list = false;
  int jobs = 0;               // points at once; 0: one per core
  std::string resume;         // finish the study in this folder (its study.json)
  // Over several packings (run/ensemble.hpp: "N" or "3,7,11"): each a whole study in
  // DIR/seeds/S/, the ensemble in DIR/ensemble.csv and DIR/summary.md; empty: one packing.
  std::string seeds;
};

int study_command(const StudyArgs& a);

}  // namespace fluidbed::app
