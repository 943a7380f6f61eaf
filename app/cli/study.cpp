// fluidbed study: speed against accuracy, stability limits and model choices (see
// app/studies/study.hpp and README.md, "Studies").
#include "cli/study.hpp"

#include <cstdio>

#include "cli/interrupt.hpp"
#include "core/errors.hpp"
#include "core/threads.hpp"
#include "studies/study.hpp"

namespace fluidbed::app {

int study_command(const StudyArgs& a) {
  using namespace study;
  if (a.list) {
    for (const Info& i : all_studies())
      std::printf("%-12s %s\n%-12s full size: %s; --size tiny: %s\n", i.name, i.title, "",
                  i.full_duration, i.tiny_duration);
    std::printf("(durations on two cores; `fluidbed study NAME --out DIR` writes DIR/study.csv, "
                "DIR/*.png and DIR/summary.md)\n");
    return 0;
  }
  std::string known;
  for (const Info& i : all_studies()) known += (known.empty() ? "" : ", ") + std::string(i.name);
  if (a.name.empty()) throw InputError("study: name a study (" + known + ") or use --list");
  const Info* info = find_study(a.name);
  if (!info) throw InputError("study: unknown study '" + a.name + "' (known: " + known + ")");
  if (a.size != "full" && a.size != "tiny")
    throw InputError("study: --size is '" + a.size + "'; expected full or tiny");
  Options o;
  o.size = a.quick || a.size == "tiny" ? Size::Tiny : Size::Full;
  o.out = a.out.empty() ? "out/study-" + a.name : a.out;
  if (!a.resume.empty()) {
    check_resume_out(a.out, a.resume, "cannot resume " + a.resume + ": ", "study");
    o.out = a.resume;
    o.resume = true;
  }
  o.workers = a.jobs;
  o.command = "fluidbed study " + a.name + (o.size == Size::Tiny ? " --size tiny" : "") +
              " --out " + o.out;
  o.stop = [] { return InterruptGuard::received() != 0; };
  o.log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  check_study_resume(*info, o);  // before the first line: a refused resume is one line
  std::printf("study %s (%s size, %d worker threads%s): %s\n", info->name,
              o.size == Size::Tiny ? "tiny" : "full", resolve_threads(o.workers),
              o.resume ? ", resumed" : "", info->title);
  Report r;
  try {
    const InterruptGuard interrupts;
    r = run_study(*info, o);
  } catch (const Interrupted&) {
    say_interrupted("fluidbed study " + std::string(info->name) +
                    (o.size == Size::Tiny ? " --size tiny" : "") + " --resume " + o.out);
    return 130;
  }
  std::printf("%d points, %d failed runs (recorded); %.0f s\n", r.points, r.failed, r.wall_time);
  std::printf("wrote %s/study.csv, %s/summary.md", o.out.c_str(), o.out.c_str());
  for (const auto& c : r.charts) std::printf(", %s", c.c_str());
  std::printf("\n");
  return 0;
}

}  // namespace fluidbed::app
