// Study 7: every way a run of these studies can fail, provoked on purpose, must be detected and
// reported in one line of words, and recorded as a failed point (never a crash). Each case is a
// scene with the one setting that breaks it; the study records what was detected and whether it
// is the failure the case provokes.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/errors.hpp"
#include "run/packed_bed.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace {
namespace fs = std::filesystem;

struct Case {
  std::string name, expected, how;
  Settings settings;
  double until = 0.2;
};

struct CaseResult {
  Case c;
  PointRun run;
};

// The bed from the packed state, as the cases that start from it share.
Settings packed_bed(Size size, const std::string& packed) {
  Settings s = bed_scene(size);
  s.particles.placement = Placement::State;
  s.particles.state_file = packed;
  return s;
}

std::vector<Case> make_cases(Size size, const std::string& packed) {
  std::vector<Case> cases;
  const double tc = contact_duration(50000.0, paper_particle_mass());
  {
    Case c{"NaN in the state", "nan", "one particle whose starting velocity is NaN (set in the settings; a scene file is refused)",
           drop_scene(0.053), 0.01};
    c.settings.particles.vy = NAN;
    cases.push_back(c);
  }
  {
    Case c{"runaway overlap", "overlap",
           "the packed bed without gas at a step of half a contact duration (time.dt = t_c / 2)",
           packed_bed(size, packed), 0.05};
    c.settings.gas.enabled = false;
    c.settings.time.dt = 0.5 * tc;
    cases.push_back(c);
  }
  {
    Case c{"particle leaves the bed", "left_bed",
           "one particle thrown up at 20 m/s out of the open top (domain.top_wall = false)",
           drop_scene(0.053), 0.02};
    c.settings.particles.y = 0.85;
    c.settings.particles.vy = 20.0;
    cases.push_back(c);
  }
  {
    Case c{"gas CFL above 1", "cfl",
           "the jetted bed with 50 particle steps per gas step (coupling.particle_steps_per_gas_step)",
           packed_bed(size, packed), 0.1};
    c.settings.coupling.particle_steps_per_gas_step = 50;
    cases.push_back(c);
  }
  {
    // Springs so soft that the bed's own weight squeezes the spheres into each other (the overlap
    // limit relaxed so that the porosity check is the one that speaks).
    Case c{"porosity out of range", "porosity",
           "a bed of very soft spheres (contact.stiffness = 10 N/m, overlap limit 0.9) settling in "
           "still air",
           bed_scene(size), 1.0};
    c.settings.particles.placement = Placement::Lattice;
    c.settings.particles.fill_height = size == Size::Tiny ? 0.12 : 0.3;
    c.settings.contact.stiffness = 10.0;
    c.settings.contact.damping = 0.02;
    c.settings.time.dt = contact_duration(10.0, paper_particle_mass()) / 30.0;
    c.settings.diagnostics.overlap_limit = 0.9;
    c.settings.inlet.kind = InletKind::None;
    c.settings.inlet.superficial_velocity = 0.0;
    cases.push_back(c);
  }
  {
    Case c{"SIMPLE does not converge", "simple",
           "the jetted bed with one SIMPLE iteration per gas step to a tolerance of 1e-12",
           packed_bed(size, packed), 0.01};
    c.settings.gas.tolerance = 1e-12;
    c.settings.gas.max_iterations = 1;
    cases.push_back(c);
  }
  return cases;
}

bool as_expected(const CaseResult& r) { return !r.run.ok && r.run.kind == r.c.expected; }

std::vector<CaseResult> measure(const Options& o) {
  if (o.log) o.log("packed bed (cached after the first time)");
  const std::string packed = packed_bed_state(bed_scene(o.size), o.log);
  const std::vector<Case> cases = make_cases(o.size, packed);
  return RunPool(o.workers).map<CaseResult>(cases.size(), [&](std::size_t i) {
    CaseResult r{cases[i], run_point(o, cases[i].settings, cases[i].until)};
    if (o.log)
      o.log("  " + r.c.name + ": " + (r.run.ok ? "NOT detected (the run completed)" : r.run.error));
    return r;
  });
}

Table table(const std::vector<CaseResult>& res) {
  Table t({"case", "provoked_by", "expected_kind", "detected_kind", "detected_as_expected",
           "sim_time_s", "wall_s", "status", "failure_kind", "failure"});
  for (const auto& r : res)
    t.add({r.c.name, r.c.how, r.c.expected, r.run.ok ? "none" : r.run.kind,
           as_expected(r) ? "yes" : "no", num(r.c.until), num(r.run.wall),
           r.run.ok ? "completed" : "failed", r.run.kind, r.run.error},
          !r.run.ok);
  return t;
}

std::vector<std::string> charts(const std::vector<CaseResult>& res, const std::string& dir) {
  chart::Chart c;
  c.title = "Failure cases: detected as provoked (1) or not (0)";
  c.x.label = "case (numbered as in summary.md)";
  c.y.label = "detected as expected";
  c.y.min = -0.2;
  c.y.max = 1.3;
  c.x.min = 0.5;
  c.x.max = static_cast<double>(res.size()) + 0.5;
  c.legend = false;
  chart::Series s;
  s.mark = chart::Mark::Points;
  s.marker_size = 12.0;
  for (std::size_t i = 0; i < res.size(); ++i) {
    s.x.push_back(static_cast<double>(i + 1));
    s.y.push_back(as_expected(res[i]) ? 1.0 : 0.0);
    s.point_labels.push_back(res[i].c.expected);
  }
  c.series.push_back(s);
  return {write_chart(dir, "failures.png", c, 1000, 500)};
}

std::string findings(const std::vector<CaseResult>& res) {
  const auto detected = std::count_if(res.begin(), res.end(), as_expected);
  std::ostringstream md;
  md << "Each case breaks one thing on purpose; the run is stopped by the check that belongs to "
        "it, with one line that names what went wrong, where and when. "
     << detected << " of " << res.size() << " detected as provoked.\n\n"
     << "| # | case | provoked by | detected | message |\n|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < res.size(); ++i) {
    const auto& r = res[i];
    md << "| " << i + 1 << " | " << r.c.name << " | " << r.c.how << " | "
       << (r.run.ok ? "no: the run completed" : r.run.kind) << " | " << r.run.error << " |\n";
  }
  md << "\nWhere each check lives: NaN, runaway overlap and a particle leaving the bed in the "
        "particle step (engine/dem); gas CFL above 1, NaN in the gas and SIMPLE that does not "
        "converge in the gas step (engine/cfd); porosity outside (0, 1] in the coupler; and, after "
        "every gas step of a run, the CFL limit and a porosity range [0.3, 1] in the run loop "
        "(engine/sim/run.cpp, RunOptions::cfl_limit and porosity_min). The integrator study adds "
        "its own: energy that grows by more than 0.1 m g D per particle in a packing at rest.\n";
  return md.str();
}

std::string advice(const std::vector<CaseResult>& /*res*/) {
  // Nothing measured changes it: every case either stops with its sentence or is a row saying
  // it was not detected.
  return
      "Nothing to choose: every failure a study can meet ends its run with a sentence, and the "
      "study goes on to its next point. When a run of yours fails, the sentence names the setting "
      "to change: a CFL failure means a shorter gas step (time.dt or "
      "coupling.particle_steps_per_gas_step), a runaway overlap or a particle leaving the bed a "
      "shorter time.dt (below about t_c / 9 = 1.5e-5 s for the paper's spheres), a porosity out of "
      "range springs too soft for the bed's weight.";
}

}  // namespace

Report failures_study(const Options& o) {
  return run_steps<std::vector<CaseResult>>(o, {measure, table, charts, findings, advice});
}

}  // namespace fluidbed::app::study
