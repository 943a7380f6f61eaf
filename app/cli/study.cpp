// fluidbed study: speed against accuracy, stability limits and model choices (see
// app/studies/common.hpp and docs/studies.md).
#include "cli/study.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/interrupt.hpp"
#include "core/errors.hpp"
#include "core/text_format.hpp"
#include "core/threads.hpp"
#include "run/ensemble.hpp"
#include "studies/common.hpp"

namespace fluidbed::app {
namespace {

namespace fs = std::filesystem;

// `study NAME --seeds`: the study once per packing, one after the other (each on every worker),
// as an ensemble (run/ensemble.hpp): each member in DIR/seeds/S/, DIR/ensemble.json says which
// study, size and seeds (a resume without --seeds takes them from there), and the ensemble's
// table and summary are written at the end (write_study_ensemble).
int study_ensemble(const study::Info& info, const study::Options& o, const StudyArgs& a) {
  using namespace study;
  const std::string head = "study " + std::string(info.name) + ": ";
  if (!info.over_packings) {
    std::string names;
    for (const Info& i : all_studies())
      if (i.over_packings) names += (names.empty() ? "" : ", ") + std::string(i.name);
    throw InputError(head + "--seeds is for the studies of the packed bed's behaviour (" + names +
                     "); this one does not start from a packing");
  }
  const char* size = o.size == Size::Tiny ? "tiny" : "full";
  const std::uint64_t first = lattice_seed(bed_scene(o.size));
  std::vector<std::uint64_t> seeds;
  if (o.resume) {
    const std::string cannot = "cannot resume " + o.out + ": ";
    const nlohmann::json j = read_ensemble_identity(o.out, "study --seeds", cannot);
    if (j.value("study", "") != info.name || j.value("size", "") != size)
      throw InputError(cannot + "it holds the study " + j.value("study", "?") + " at size " +
                       j.value("size", "?"));
    seeds = j.value("seeds", std::vector<std::uint64_t>());
    if (!a.seeds.empty() && parse_seeds(a.seeds, first) != seeds)
      throw InputError(cannot + "--seeds " + a.seeds + " is not its --seeds " +
                       j.value("seeds_option", std::string()));
  } else {
    seeds = parse_seeds(a.seeds, first);
  }
  std::string seeds_option = a.seeds;
  if (o.resume)
    seeds_option = read_ensemble_identity(o.out, "study --seeds", "").value("seeds_option", a.seeds);
  std::vector<Options> members;
  for (std::uint64_t seed : seeds) {
    Options m = o;
    m.out = member_dir(o.out, seed);
    m.seed = seed;
    m.resume = o.resume && fs::exists(fs::path(m.out) / "study.json");
    m.command = o.command + " --seeds " + seeds_option + " (seed " + std::to_string(seed) + ")";
    check_study_resume(info, m);  // every member before the first point
    members.push_back(std::move(m));
  }
  std::error_code ec;
  for (const char* f : {"ensemble.csv", "summary.md"}) fs::remove(fs::path(o.out) / f, ec);
  std::printf("study %s over %zu packings (%s size, %d worker threads%s): %s\n", info.name,
              seeds.size(), size, resolve_threads(o.workers), o.resume ? ", resumed" : "",
              info.title);
  int points = 0, failed = 0;
  EnsembleJob job;
  job.dir = o.out;
  job.seeds = seeds;
  job.identity = {{"kind", "study --seeds"}, {"study", info.name}, {"size", size},
                  {"seeds_option", seeds_option}, {"command", o.command + " --seeds " + seeds_option}};
  job.summary = false;  // the study's own: ensemble.csv and summary.md
  job.member = [&](std::size_t k, std::uint64_t seed,
                   const std::string&) -> std::optional<nlohmann::json> {
    stop_if_asked(members[k]);  // an interrupted member stops the rest before they begin
    std::printf("== seed %llu\n", static_cast<unsigned long long>(seed));
    std::fflush(stdout);
    const Report r = run_study(info, members[k]);
    points += r.points;
    failed += r.failed;
    return nlohmann::json::object();
  };
  try {
    const InterruptGuard interrupts;
    run_ensemble(job, o.resume);
  } catch (const Interrupted&) {
    say_interrupted("fluidbed study " + std::string(info.name) +
                    (o.size == Size::Tiny ? " --size tiny" : "") + " --resume " + o.out);
    return 130;
  }
  write_study_ensemble(info, o.out, seeds, o.size);
  std::printf("%d points over %zu packings, %d failed runs (recorded)\n", points, seeds.size(),
              failed);
  std::printf("wrote %s/ensemble.csv, %s/summary.md and %s/seeds/S/\n", o.out.c_str(),
              o.out.c_str(), o.out.c_str());
  return 0;
}

// `study sensitivity`: a scene the user names, its points over --seeds inside the one study.
int scene_study(const study::Info& info, study::Options o, const StudyArgs& a) {
  using namespace study;
  const std::string head = "study " + std::string(info.name) + ": ";
  if (o.size == Size::Tiny) throw InputError(head + "--size is for the built-in studies");
  // The scene by its absolute path: a resume from another folder finds the same file.
  o.scene_study = {a.scene.empty() ? a.scene : std::filesystem::absolute(a.scene).string(),
                   a.overrides, a.vary, a.until, a.seeds};
  if (o.resume && a.scene.empty() && a.vary.empty() && a.overrides.empty() && a.until == 0.0 &&
      a.seeds.empty())
    o.scene_study = stored_scene_study(o.out);  // resumed as it was started
  if (o.scene_study.scene.empty()) throw InputError(head + "name the scene: --scene SCENE.toml");
  if (o.scene_study.vary.empty())
    throw InputError(head + "name what to vary: --vary KEY=V1,V2 (or KEY1,KEY2=A1:B1,A2:B2)");
  o.command = "fluidbed study " + std::string(info.name) + " --scene " + o.scene_study.scene;
  for (const std::string& v : o.scene_study.vary) o.command += " --vary '" + v + "'";
  for (const std::string& v : o.scene_study.overrides) o.command += " --set '" + v + "'";
  if (o.scene_study.until > 0.0) o.command += " --until " + format_number("%g", o.scene_study.until);
  if (!o.scene_study.seeds.empty()) o.command += " --seeds " + o.scene_study.seeds;
  o.command += " --out " + o.out;
  check_study_resume(info, o);  // before the first line: a refused resume is one line
  std::printf("study %s of %s (%d worker threads%s)\n", info.name, o.scene_study.scene.c_str(),
              resolve_threads(o.workers), o.resume ? ", resumed" : "");
  Report r;
  try {
    const InterruptGuard interrupts;
    r = run_study(info, o);
  } catch (const Interrupted&) {
    say_interrupted("fluidbed study " + std::string(info.name) + " --out " + o.out + " --resume");
    return 130;
  }
  std::printf("%d points, %d failed (recorded); %.0f s\n", r.points, r.failed, r.wall_time);
  std::printf("wrote %s/study.csv, %s/runs.csv, %s/summary.md", o.out.c_str(), o.out.c_str(),
              o.out.c_str());
  for (const auto& c : r.charts) std::printf(", %s", c.c_str());
  std::printf("\n");
  return 0;
}

}  // namespace

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
  o.resume = o.resume || a.resume_out;
  o.workers = a.jobs;
  o.command = "fluidbed study " + a.name + (o.size == Size::Tiny ? " --size tiny" : "") +
              " --out " + o.out;
  o.stop = [] { return InterruptGuard::received() != 0; };
  o.log = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  if (info->takes_scene) return scene_study(*info, o, a);
  for (const auto& [given, option] : {std::pair{!a.scene.empty(), "--scene"},
                                      {!a.vary.empty(), "--vary"}, {!a.overrides.empty(), "--set"},
                                      {a.until > 0.0, "--until"}})
    if (given)
      throw InputError("study " + a.name + ": " + option +
                       " is for study sensitivity; this study runs its own scenes");
  if (!a.seeds.empty() || (o.resume && holds_ensemble(o.out)))
    return study_ensemble(*info, o, a);
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
