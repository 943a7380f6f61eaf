// Study: where the particle model conserves energy and how well its numbers do. A closed box
// (the paper's slab with a top wall) of 2400 elastic, frictionless spheres without gas, started
// from the random lattice in the lower half, falls for a while and stays agitated for ever: nothing
// dissipates, so the energy budget's residual (analysis/energy_budget.hpp) is the integration
// error alone. From that one agitated state, each integrator and contact form runs the same
// simulated time at the paper's step and at a tenth of it.
#include <cmath>
#include <sstream>

#include <filesystem>

#include "core/errors.hpp"
#include "sim/simulation.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace {

struct BoxPoint {
  Integrator integrator = Integrator::Newmark;
  Displacement displacement = Displacement::Incremental;
  double dt = 0.0, until = 0.0;
  PointRun run;
  double residual_per_s = NAN;   // W
  double kinetic_mean = NAN;     // J, the box's mean kinetic energy over the run
};

struct Box {
  Size size = Size::Full;
  int particles = 0;
  double agitate = 0.0;  // s, the fall from the lattice before the variants start
  double scale = 0.0;  // J, m g D per particle times the count
  std::vector<BoxPoint> pts;
};

Settings box_scene(Size size) {
  Settings s;
  s.scene.name = "elastic-box";
  s.scene.kind = SceneKind::Packing;
  s.domain.top_wall = true;
  s.gas.enabled = false;
  s.contact.damping = 0.0;
  s.contact.friction = 0.0;
  s.particles.placement = Placement::Lattice;
  s.particles.fill_height = 0.45;
  if (size == Size::Tiny) {
    s.particles.count = 300;
    s.domain.width = 0.06;
    s.domain.height = 0.3;
    s.particles.fill_height = 0.15;
  }
  s.diagnostics.output_interval = 1e-3;
  return s;
}

Box measure(const Options& o) {
  Box m;
  m.size = o.size;
  const bool tiny = o.size == Size::Tiny;
  Settings base = box_scene(o.size);
  m.particles = base.particles.count;
  m.scale = paper_particle_mass() * base.physics.gravity * base.particles.diameter * m.particles;
  // The agitated start, shared by every point: the lattice falls at the paper's step.
  m.agitate = tiny ? 0.1 : 0.3;
  {
    Settings a = base;
    a.time.integrator = Integrator::VelocityVerlet;
    a.contact.displacement = Displacement::Geometric;
    Simulation sim(a);
    RunOptions opt;
    opt.until = m.agitate;
    run_to_end(o, sim, opt);
    const std::string state = std::filesystem::absolute(std::filesystem::path(o.out) / "agitated.state").string();
    sim.save_state(state);
    base.particles.placement = Placement::State;
    base.particles.state_file = state;
    if (o.log) o.log("  agitated start after " + num(m.agitate) + " s of falling: " + state);
  }
  for (Integrator in : {Integrator::Newmark, Integrator::VelocityVerlet, Integrator::SymplecticEuler})
    for (Displacement d : {Displacement::Incremental, Displacement::Geometric})
      for (double dt : {1.5e-5, 1.5e-6}) {
        BoxPoint p;
        p.integrator = in;
        p.displacement = d;
        p.dt = dt;
        p.until = tiny ? 0.05 : 0.2;  // s, from the agitated start
        m.pts.push_back(p);
      }
  RunPool(o.workers).map<int>(m.pts.size(), [&](std::size_t i) {
    BoxPoint& p = m.pts[i];
    Settings s = base;
    s.time.integrator = p.integrator;
    s.contact.displacement = p.displacement;
    s.time.dt = p.dt;
    s.diagnostics.output_interval = p.until / 100.0;
    p.run = run_point(o, s, p.until);
    if (p.run.ok) {
      const auto& e = p.run.result.summary["energy"];
      p.residual_per_s = e.value("residual_per_s_w", NAN);
      double ke = 0.0;
      for (const auto& row : p.run.result.rows) ke += row.kinetic_energy;
      p.kinetic_mean = ke / static_cast<double>(std::max<std::size_t>(1, p.run.result.rows.size()));
    }
    if (o.log)
      o.log("  " + std::string(option_string(p.integrator)) + " " + option_string(p.displacement) +
            " dt " + num(p.dt) + ": " +
            (p.run.ok ? fmt("residual %.3g W", p.residual_per_s) : "failed: " + p.run.error));
    return 0;
  });
  return m;
}

Table table(const Box& m) {
  Table t({"integrator", "contact_displacement", "dt_s", "sim_time_s", "particles",
           "residual_j", "residual_per_s_w", "residual_per_s_per_mgd", "kinetic_energy_mean_j",
           "mechanical_change_j", "max_overlap_ratio", "cost_cpu_s_per_sim_s", "status",
           "failure_kind", "failure"});
  for (const auto& p : m.pts) {
    const auto& j = p.run.result.summary;
    const auto e = p.run.ok ? j["energy"] : nlohmann::json::object();
    t.add({option_string(p.integrator), option_string(p.displacement), num(p.dt), num(p.until),
           num(m.particles), num(p.run.ok ? e.value("residual_j", NAN) : NAN),
           num(p.residual_per_s), num(p.residual_per_s / m.scale), num(p.kinetic_mean),
           num(p.run.ok ? e.value("mechanical_change_j", NAN) : NAN),
           num(p.run.ok ? json_number(j, "max_overlap_ratio") : NAN),
           num(p.run.ok ? p.run.cpu / p.until : NAN), p.run.ok ? "ok" : "failed",
           p.run.ok ? "" : p.run.kind, p.run.ok ? "" : p.run.error},
          !p.run.ok);
  }
  return t;
}

std::string variant_name(const BoxPoint& p) {
  return std::string(option_string(p.integrator)) + ", " + option_string(p.displacement);
}

std::vector<std::string> charts(const Box& m, const std::string& dir) {
  std::vector<chart::Chart> panels;
  for (double dt : {1.5e-5, 1.5e-6}) {
    chart::Chart c;
    c.title = "Energy residual, dt = " + fmt("%.2g s", dt);
    c.x.label = "time (s)";
    c.y.label = "residual / (N m g D)";
    for (const auto& p : m.pts) {
      if (p.dt != dt || !p.run.ok) continue;
      chart::Series s;
      s.label = variant_name(p);
      s.dashed = p.displacement == Displacement::Geometric;
      s.width = 1.5;
      for (const auto& row : p.run.result.rows) {
        s.x.push_back(row.t);
        s.y.push_back(row.energy.residual / m.scale);
      }
      c.series.push_back(s);
    }
    c.hlines.push_back({0.0, "", {150, 150, 150}, false, 1.0});
    panels.push_back(c);
  }
  chart::Chart rate = log_log_chart("Residual per simulated second against the step", "dt (s)",
                                    "|residual| per s / (N m g D)");
  for (Integrator in : {Integrator::Newmark, Integrator::VelocityVerlet, Integrator::SymplecticEuler})
    for (Displacement d : {Displacement::Incremental, Displacement::Geometric}) {
      chart::Series s;
      s.mark = chart::Mark::LinePoints;
      s.dashed = d == Displacement::Geometric;
      for (const auto& p : m.pts) {
        if (p.integrator != in || p.displacement != d || !p.run.ok) continue;
        s.label = variant_name(p);
        s.x.push_back(p.dt);
        s.y.push_back(std::fabs(p.residual_per_s) / m.scale);
      }
      if (!s.x.empty()) rate.series.push_back(s);
    }
  panels.push_back(rate);
  return {write_grid(dir, "energy.png", panels, 3, 700, 520,
                     "Elastic frictionless box, no gas: what the energy budget leaves over")};
}

std::string findings(const Box& m) {
  std::ostringstream md;
  md << "A closed box " << (m.size == Size::Tiny ? "(tiny: 0.06 x 0.3 m)" : "(the paper's slab, 0.15 x 0.9 m, with a top wall)")
     << " of " << m.particles << " elastic, frictionless spheres (eta = 0, gamma = 0) without gas, "
     << "falling from the random lattice for " << num(m.agitate) << " s (velocity Verlet, geometric, "
     << "1.5e-5 s) and then bouncing for ever; each variant runs from that state. Nothing "
     << "dissipates, so the budget's "
     << "residual is the integration error. Scale: N m g D = " << fmt("%.3g J", m.scale) << ".\n\n"
     << "| integrator | contact | dt (s) | simulated (s) | residual per s (W) | per s / (N m g D) | "
        "mean kinetic energy (J) | max overlap |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& p : m.pts) {
    md << "| " << option_string(p.integrator) << " | " << option_string(p.displacement) << " | "
       << fmt("%.2g", p.dt) << " | " << fmt("%.3g", p.until) << " | ";
    if (p.run.ok)
      md << fmt("%+.3g", p.residual_per_s) << " | " << fmt("%+.3g", p.residual_per_s / m.scale)
         << " | " << fmt("%.3g", p.kinetic_mean) << " | "
         << fmt("%.3g %%", 100.0 * json_number(p.run.result.summary, "max_overlap_ratio")) << " |\n";
    else
      md << "failed: " << p.run.error << " | | | |\n";
  }
  // How the residual falls with the step: its order, log10 of the ratio over a tenfold step.
  md << "\nOrder of the residual in dt (log10 of |residual at 1.5e-5| / |residual at 1.5e-6|):";
  for (const auto& a : m.pts) {
    if (a.dt != 1.5e-5 || !a.run.ok) continue;
    for (const auto& b : m.pts)
      if (b.dt == 1.5e-6 && b.run.ok && b.integrator == a.integrator && b.displacement == a.displacement)
        md << " " << variant_name(a) << fmt(" %.1f;", std::log10(std::fabs(a.residual_per_s / b.residual_per_s)));
  }
  md << "\n";
  return md.str();
}

std::string advice(const Box& m) {
  const BoxPoint* best = nullptr;
  const BoxPoint* paper = nullptr;
  for (const auto& p : m.pts) {
    if (!p.run.ok || p.dt != 1.5e-5) continue;
    if (!best || std::fabs(p.residual_per_s) < std::fabs(best->residual_per_s)) best = &p;
    if (p.integrator == Integrator::Newmark && p.displacement == Displacement::Incremental) paper = &p;
  }
  std::ostringstream adv;
  if (!best || !paper) return "Runs at the paper's step failed; see the table.";
  const double mean_ke = paper->kinetic_mean;
  adv << "At the paper's step the paper's scheme (Newmark, incremental) leaves "
      << fmt("%+.3g W", paper->residual_per_s) << " unaccounted for, "
      << fmt("%.2g", std::fabs(paper->residual_per_s) / mean_ke)
      << " of the box's mean kinetic energy per simulated second; the best variant there is "
      << variant_name(*best) << " (" << fmt("%+.3g W", best->residual_per_s) << "). "
      << (paper->residual_per_s > 0.0 ? "The sign is a gain: the scheme feeds energy into an undamped bed, "
                                        "which agitates it beyond what the physics would."
                                      : "The sign is a loss: the scheme itself damps an undamped bed.")
      << " Where energy conservation matters (the ideal case), judge the run by this residual "
         "against the energy the gas puts in (the run's summary.json `energy`).";
  return adv.str();
}

}  // namespace

Report energy_study(const Options& o) {
  return run_steps<Box>(o, {measure, table, charts, findings, advice});
}

}  // namespace fluidbed::app::study
