// Study 5: what each physics module costs, and whether a scene that does not need it pays for it.
// The same packed bed run for a short time with modules switched on one by one: particles alone
// without and with friction (the tangential spring and its history), then the gas at rest, then
// the jetted bed, and the gas alone (the bed held fixed); the drop scene (one particle, no gas)
// beside them. Each step's time is split by phase (the engine's own clocks: neighbour search,
// contacts, integration, porosity and drag, gas).
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/errors.hpp"
#include "run/packed_bed.hpp"
#include "sim/simulation.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace {
namespace fs = std::filesystem;

struct ModuleConfig {
  std::string label, needs;
  std::vector<std::string> overrides;
  bool drop = false;
};

struct ModuleResult {
  ModuleConfig cfg;
  bool ok = false;
  std::string error, kind;
  std::size_t particles = 0;
  std::int64_t steps = 0;
  double wall = 0.0, sim_time = 0.0, cpu = 0.0;
  double phase[static_cast<int>(Phase::Count)] = {};  // s
  double us_per_step() const { return steps > 0 ? 1e6 * wall / static_cast<double>(steps) : NAN; }
  double phase_us(int k) const { return steps > 0 ? 1e6 * phase[k] / static_cast<double>(steps) : NAN; }
};

// What a stored configuration keeps (stored_point): all but its configuration.
template <class R, class F>
void module_fields(R& r, F&& f) {
  f("ok", r.ok);
  f("error", r.error);
  f("kind", r.kind);
  f("particles", r.particles);
  f("steps", r.steps);
  f("wall", r.wall);
  f("sim_time", r.sim_time);
  f("cpu", r.cpu);
  static const char* const phases[] = {"phase_0", "phase_1", "phase_2", "phase_3", "phase_4",
                                       "phase_5", "phase_6", "phase_7", "phase_8", "phase_9"};
  static_assert(static_cast<int>(Phase::Count) <= 10);
  for (int k = 0; k < static_cast<int>(Phase::Count); ++k) f(phases[k], r.phase[k]);
}
const auto kModuleFields = [](auto& r, auto&& f) { module_fields(r, f); };

// One configuration's run (s: its settings), measured.
ModuleResult measure_module(const Options& o, const Settings& s, double until) {
  ModuleResult r;
  try {
    Simulation sim(s);
    sim.dem().phase_times().reset();
    RunOptions opt;
    opt.until = until;
    const double cpu0 = thread_cpu_seconds();
    const RunResult res = run_to_end(o, sim, opt);
    r.cpu = thread_cpu_seconds() - cpu0;
    r.steps = res.summary["steps"].get<std::int64_t>();
    r.wall = res.summary["wall_time_s"].get<double>();
    r.sim_time = res.summary["sim_time_s"].get<double>();
    r.particles = sim.particle_count();
    for (int k = 0; k < static_cast<int>(Phase::Count); ++k)
      r.phase[k] = sim.dem().phase_times().seconds(static_cast<Phase>(k));
    r.ok = true;
  } catch (const SimulationFailure& e) {
    r.error = e.what();
    r.kind = failure_kind(r.error);
  }
  return r;
}

// A configuration as a stored point (stored_point).
ModuleResult run_module(const Options& o, const ModuleConfig& c, const Settings& bed,
                        double until) {
  Settings s = c.drop ? drop_scene(0.053) : bed;
  for (const auto& w : c.overrides) {
    // The few switches this study uses, applied to the settings directly.
    if (w == "no-gas") s.gas.enabled = false;
    if (w == "frictionless") {
      s.contact.friction = 0.0;
      s.contact.tangential_stiffness_ratio = 0.0;
      s.contact.tangential_damping_ratio = 0.0;
    }
    if (w == "gas-at-rest") {
      s.inlet.kind = InletKind::None;
      s.inlet.superficial_velocity = 0.0;
    }
    if (w == "frozen") s.particles.frozen = true;
  }
  ModuleResult r = stored_fields<ModuleResult>(o, run_definition("module", s, until), kModuleFields,
                                               [&] { return measure_module(o, s, until); });
  r.cfg = c;
  return r;
}

// What the study measured: each configuration of modules run from the same packed bed.
struct Modules {
  bool tiny = false;
  double until = 0.0;      // s, each configuration's run
  int particles = 0;       // of the bed
  std::vector<ModuleResult> res;  // in the order of the configurations in summary.md
};

Modules measure(const Options& o) {
  Modules m;
  m.tiny = o.size == Size::Tiny;
  m.until = m.tiny ? 0.05 : 0.1;
  Settings bed = bed_scene(o.size);
  if (o.log) o.log("packed bed (cached after the first time)");
  bed.particles.placement = Placement::State;
  bed.particles.state_file = packed_bed_state(bed_scene(o.size), o.log);
  bed.diagnostics.averaging_start = 0.0;
  const std::vector<ModuleConfig> cfgs = {
      {"drop: 1 particle, no gas", "contacts with a wall", {}, true},
      {"particles, frictionless", "normal contacts only", {"no-gas", "frictionless"}, false},
      {"+ friction (tangential history)", "friction", {"no-gas"}, false},
      {"+ gas at rest", "gas, no inflow (the packing)", {"gas-at-rest"}, false},
      {"+ jet at 2.8 m/s (full model)", "everything", {}, false},
      {"gas alone (bed held fixed)", "gas through a fixed bed", {"frozen"}, false},
  };
  m.particles = bed.particles.count;
  m.res = RunPool(o.workers).map<ModuleResult>(cfgs.size(), [&](std::size_t i) {
    ModuleResult r = run_module(o, cfgs[i], bed, m.until);
    if (o.log)
      o.log("  " + r.cfg.label + ": " +
            (r.ok ? fmt("%.1f us per step", r.us_per_step()) : "failed: " + r.error));
    return r;
  });
  return m;
}

Table table(const Modules& m) {
  std::vector<std::string> cols = {"configuration", "needs", "particles", "steps", "sim_time_s",
                                   "wall_s", "cpu_s", "us_per_step", "cpu_us_per_step",
                                   "us_per_particle_step", "cost_wall_s_per_sim_s"};
  const char* phase_cols[] = {"neighbours_us_per_step", "contacts_us_per_step",
                              "integration_us_per_step", "porosity_drag_us_per_step",
                              "gas_us_per_step"};
  for (const char* c : phase_cols) cols.push_back(c);
  for (const char* c : {"status", "failure_kind", "failure"}) cols.push_back(c);
  Table t(cols);
  for (const auto& r : m.res) {
    std::vector<std::string> row = {
        r.cfg.label, r.cfg.needs, std::to_string(r.particles), std::to_string(r.steps),
        num(r.sim_time), num(r.wall), num(r.cpu), num(r.us_per_step()),
        num(r.steps > 0 ? 1e6 * r.cpu / static_cast<double>(r.steps) : NAN),
        num(r.us_per_step() / static_cast<double>(std::max<std::size_t>(r.particles, 1))),
        num(r.sim_time > 0 ? r.wall / r.sim_time : NAN)};
    for (int k = 0; k < static_cast<int>(Phase::Count); ++k) row.push_back(num(r.phase_us(k)));
    row.push_back(r.ok ? "ok" : "failed");
    row.push_back(r.kind);
    row.push_back(r.error);
    t.add(row, !r.ok);
  }
  return t;
}

std::vector<std::string> charts(const Modules& m, const std::string& dir) {
  // Time per step of each phase (points) and in all (line), configurations 2-6, labelled.
  chart::Chart c;
  c.title = "Time per step by phase (" + std::to_string(m.particles) + " particles)";
  c.x.label = "configuration (numbered as in summary.md)";
  c.y.label = "microseconds per step";
  c.x.min = 1.5;
  c.x.max = static_cast<double>(m.res.size()) + 0.9;
  c.y.min = 0.0;
  for (int k = 0; k < static_cast<int>(Phase::Count); ++k) {
    chart::Series s;
    s.label = phase_name(static_cast<Phase>(k));
    s.mark = chart::Mark::Points;
    s.shape = static_cast<chart::Shape>(k % 4);
    s.marker_size = 9.0;
    s.colour = chart::palette(static_cast<std::size_t>(k));
    for (std::size_t i = 1; i < m.res.size(); ++i) {
      s.x.push_back(static_cast<double>(i + 1));
      s.y.push_back(m.res[i].ok ? m.res[i].phase_us(k) : NAN);
    }
    c.series.push_back(s);
  }
  chart::Series total;
  total.label = "whole step";
  total.mark = chart::Mark::LinePoints;
  total.colour = chart::Rgb{40, 40, 40};
  for (std::size_t i = 1; i < m.res.size(); ++i) {
    total.x.push_back(static_cast<double>(i + 1));
    total.y.push_back(m.res[i].ok ? m.res[i].us_per_step() : NAN);
    total.point_labels.push_back(m.res[i].cfg.label);
  }
  c.series.push_back(total);
  return {write_chart(dir, "modules.png", c)};
}

std::string findings(const Modules& m) {
  std::ostringstream md;
  md << "Each configuration runs " << m.until << " s from the same packed bed ("
     << m.particles << " particles" << (m.tiny ? ", the tiny bed" : ", the paper's bed")
     << "), one thread, with the other configurations running beside it; the time of each phase "
        "is the engine's own clock. Rotation has no switch: the spin is integrated with the "
        "position in the integration phase, so that phase's time is an upper bound of its cost.\n\n"
        "The phases are wall time; the CPU column is the thread's CPU time per step, which other "
        "programs sharing the machine do not inflate.\n\n"
        "| # | configuration | needs | us per step | CPU us per step | neighbours | contacts | "
        "integration | porosity and drag | gas |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < m.res.size(); ++i) {
    const auto& r = m.res[i];
    md << "| " << i + 1 << " | " << r.cfg.label << " | " << r.cfg.needs << " | ";
    if (!r.ok) {
      md << "failed: " << r.error << " | | | | | | |\n";
      continue;
    }
    md << fmt("%.1f", r.us_per_step()) << " | "
       << fmt("%.1f", 1e6 * r.cpu / static_cast<double>(std::max<std::int64_t>(r.steps, 1)));
    for (int k = 0; k < static_cast<int>(Phase::Count); ++k) md << " | " << fmt("%.1f", r.phase_us(k));
    md << " |\n";
  }
  return md.str();
}

std::string advice(const Modules& m) {
  std::ostringstream adv;
  const int kC = static_cast<int>(Phase::Contacts), kG = static_cast<int>(Phase::Gas),
            kD = static_cast<int>(Phase::Coupling);
  if (m.res[1].ok && m.res[2].ok && m.res[3].ok && m.res[4].ok) {
    const double fric = m.res[2].phase_us(kC) / m.res[1].phase_us(kC) - 1.0;
    const double gas_rest = m.res[3].us_per_step() / m.res[2].us_per_step();
    adv << "Leave out what a scene does not need, and the gas most of all: a scene without "
           "[gas] spends nothing on it (0 us in the gas and drag phases), while the gas at rest "
           "already makes a step "
        << fmt("%.1f", gas_rest) << " times as long as the particles' alone ("
        << fmt("%.0f", m.res[3].phase_us(kD)) << " us porosity and drag, "
        << fmt("%.0f", m.res[3].phase_us(kG)) << " us gas per step). The contact pass with "
           "friction takes "
        << fmt("%+.0f %%", 100.0 * fric) << " against the frictionless one"
        << (std::fabs(fric) < 0.3
                ? ", no more than the timing noise of runs sharing the cores: the tangential "
                  "spring and its history are computed whether or not a scene has friction (the "
                  "contact kernel has no frictionless variant), so a frictionless scene "
                  "(ideal.toml) neither pays nor saves much there."
                : ": friction has a cost of its own that frictionless scenes do not pay.")
        << " A packing that only needs the particles to settle can drop the gas (still air "
           "changes little of a packing of 4 mm glass).";
  } else {
    adv << "Some configurations failed; see the table.";
  }
  return adv.str();
}

}  // namespace

Report modules_study(const Options& o) {
  return run_steps<Modules>(o, {measure, table, charts, findings, advice});
}

}  // namespace fluidbed::app::study
