// Study `sensitivity`: which settings decide a scene's figures (studies/sensitivity.hpp).
#include "studies/sensitivity.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "run/ensemble.hpp"
#include "run/packed_bed.hpp"
#include "scene/scene_loader.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace fs = std::filesystem;

namespace {

// TEXT split at SEP where no bracket or quote is open.
std::vector<std::string> split_top(const std::string& text, char sep) {
  std::vector<std::string> parts(1);
  int depth = 0;
  char quote = 0;
  for (char c : text) {
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == sep && depth == 0) {
      parts.emplace_back();
      continue;
    }
    parts.back() += c;
  }
  return parts;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

}  // namespace

Variation parse_variation(const std::string& text) {
  const std::string head = "study sensitivity: --vary " + text + ": ";
  Variation v;
  v.text = text;
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw InputError(head + "expected KEY=V1,V2 or KEY1,KEY2=A1:B1,A2:B2");
  for (const std::string& k : split_top(text.substr(0, eq), ',')) {
    const std::string key = trim(k);
    if (key.empty() || key.find('.') == std::string::npos)
      throw InputError(head + "a key is 'section.key' (e.g. gas.cells_x), not '" + key + "'");
    if (std::find(v.keys.begin(), v.keys.end(), key) != v.keys.end())
      throw InputError(head + "the key " + key + " is given twice");
    v.keys.push_back(key);
  }
  for (const std::string& t : split_top(text.substr(eq + 1), ',')) {
    std::vector<std::string> tuple;
    for (const std::string& x : v.keys.size() > 1 ? split_top(t, ':') : std::vector{t})
      tuple.push_back(trim(x));
    if (tuple.size() != v.keys.size())
      throw InputError(head + "the value '" + trim(t) + "' has " + std::to_string(tuple.size()) +
                       " parts for " + std::to_string(v.keys.size()) + " keys (A1:B1 for KEY1,KEY2)");
    for (const std::string& x : tuple)
      if (x.empty()) throw InputError(head + "an empty value");
    v.values.push_back(std::move(tuple));
  }
  return v;
}

std::string scene_value(const Settings& s, const std::string& key) {
  const auto dot = key.find('.');
  const std::string section = "[" + key.substr(0, dot) + "]", name = key.substr(dot + 1);
  std::istringstream in(to_toml(s));
  std::string line, at;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '[') {
      at = line;
      continue;
    }
    if (at != section || line.rfind(name + " = ", 0) != 0) continue;
    std::string value = line.substr(name.size() + 3);
    return trim(value.substr(0, value.find("  #")));
  }
  return "";
}

std::vector<SensitivityPoint> sensitivity_points(const Settings& base,
                                                 const std::vector<Variation>& variations) {
  std::vector<SensitivityPoint> points(1);
  points[0].label = "base";
  for (std::size_t v = 0; v < variations.size(); ++v) {
    const Variation& var = variations[v];
    auto varied = [&](const char* key) {
      return std::find(var.keys.begin(), var.keys.end(), key) != var.keys.end();
    };
    std::string keys;
    for (const std::string& k : var.keys) keys += (keys.empty() ? "" : ",") + k;
    for (std::size_t j = 0; j < var.values.size(); ++j) {
      SensitivityPoint p;
      p.variation = static_cast<int>(v);
      p.value = j;
      std::string values;
      for (std::size_t k = 0; k < var.keys.size(); ++k) {
        p.overrides.push_back(var.keys[k] + "=" + var.values[j][k]);
        values += (k ? ":" : "") + var.values[j][k];
      }
      p.label = keys + "=" + values;
      points.push_back(std::move(p));
    }
    // What the tuple alone would move besides itself: held at the base's (below, once the
    // point's own values are known).
    const bool hold_gas_step = varied("time.dt") && !varied("coupling.particle_steps_per_gas_step");
    const bool hold_restitution = varied("contact.stiffness") && !varied("contact.damping");
    if (!hold_gas_step && !hold_restitution) continue;
    for (SensitivityPoint& p : points) {
      if (p.variation != static_cast<int>(v)) continue;
      Settings s = base;
      try {
        // The tuple's own values, read the way the scene reads them.
        s = parse_scene(to_toml(base), "the base scene", p.overrides);
      } catch (const InputError&) {
        continue;  // refused with the point's own words when the study builds it
      }
      if (hold_gas_step) {
        const double gas_dt = base.time.dt * base.coupling.particle_steps_per_gas_step;
        const long n = std::max(1L, std::lround(gas_dt / s.time.dt));
        p.overrides.push_back("coupling.particle_steps_per_gas_step=" + std::to_string(n));
        const double now = static_cast<double>(n) * s.time.dt;
        p.held = fmt("gas step held at %g s", gas_dt) +
                 (std::fabs(now - gas_dt) > 1e-9 * gas_dt
                      ? fmt(" (nearest: %g s", now) + ", " + std::to_string(n) + " steps)"
                      : " (" + std::to_string(n) + " particle steps per gas step)");
      }
      if (hold_restitution) {
        const double damping =
            base.contact.damping * std::sqrt(s.contact.stiffness / base.contact.stiffness);
        p.overrides.push_back("contact.damping=" + exact(damping));
        p.held += (p.held.empty() ? "" : "; ") +
                  fmt("restitution held: damping %.4g kg/s", damping);
      }
    }
  }
  return points;
}

}  // namespace fluidbed::app::study

namespace fluidbed::app::study {
namespace {

// One figure of a run: a number of its summary.json (NaN where it has none), or of its cost.
struct Figure {
  std::string column, heading;  // study.csv's column; the charts' and summary's words
  std::function<double(const PointRun&)> of;
  bool chart = true;            // drawn in the variation's chart
};

double regular(const nlohmann::json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_string()) return NAN;
  return j[key].get<std::string>().rfind("regular cycle", 0) == 0 ? 1.0 : 0.0;
}

// The figures every run is measured by: dp, each probe, the bed top and the column-mean height,
// the bubbles, and the cost.
std::vector<Figure> figures(std::size_t probes, double until) {
  using J = const PointRun&;
  std::vector<Figure> f = {
      {"dp_mean_pa", "mean dp (Pa)", [](J r) { return json_number(r.result.summary, "dp_mean_pa"); }, false},
      {"dp_std_pa", "dp std (Pa)", [](J r) { return json_number(r.result.summary, "dp_std_pa"); }},
      {"dp_peak_hz", "dp spectrum peak (Hz)",
       [](J r) { return json_number(r.result.summary, "dp_spectrum", "dominant_frequency_hz"); }},
      {"dp_regular", "dp regular cycle (share)",
       [](J r) { return regular(r.result.summary, "dp_cycle"); }, false}};
  for (std::size_t k = 0; k < probes; ++k) {
    const std::string n = std::to_string(k + 1);
    auto probe = [k](J r, const char* key) -> double {
      const nlohmann::json& s = r.result.summary;
      if (!s.contains("probes") || !s["probes"].is_array() || s["probes"].size() <= k) return NAN;
      return json_number(s["probes"][k], key);
    };
    f.push_back({"probe_" + n + "_std_pa", "probe " + n + " std (Pa)",
                 [probe](J r) { return probe(r, "std_pa"); }});
    f.push_back({"probe_" + n + "_peak_hz", "probe " + n + " spectrum peak (Hz)",
                 [probe](J r) { return probe(r, "peak_hz"); }});
    f.push_back({"probe_" + n + "_regular", "probe " + n + " regular cycle (share)",
                 [k](J r) -> double {
                   const nlohmann::json& s = r.result.summary;
                   if (!s.contains("probes") || s["probes"].size() <= k) return NAN;
                   return regular(s["probes"][k], "cycle");
                 }, false});
  }
  const std::vector<Figure> rest = {
      {"bed_top_mean_m", "bed top, mean (m)", [](J r) { return json_number(r.result.summary, "bed_top_mean_m"); }},
      {"bed_top_min_m", "bed top, min (m)", [](J r) { return json_number(r.result.summary, "bed_top_min_m"); }, false},
      {"bed_top_max_m", "bed top, max (m)", [](J r) { return json_number(r.result.summary, "bed_top_max_m"); }},
      {"bed_top_peak_hz", "bed top spectrum peak (Hz)", [](J r) { return json_number(r.result.summary, "bed_top_peak_hz"); }, false},
      {"bed_height_mean_m", "column-mean bed height (m)", [](J r) { return json_number(r.result.summary, "bed_height_mean_m"); }, false},
      {"bubbles_formed_per_s", "bubbles formed per s",
       [](J r) { return json_number(r.result.summary, "bubbles", "formed_per_s"); }},
      {"bubbles_mean_d_eq_m", "bubble mean D_e (m)",
       [](J r) { return json_number(r.result.summary, "bubbles", "mean_d_eq_m"); }, false},
      {"cost_cpu_s_per_sim_s", "cost (CPU s per simulated s)",
       [until](J r) { return r.ok ? r.cpu / until : NAN; }}};
  f.insert(f.end(), rest.begin(), rest.end());
  return f;
}

struct Point {
  SensitivityPoint def;
  Settings scene;                     // its resolved scene (the base's packing seed)
  std::vector<PointRun> runs;         // one a seed
  std::vector<SampleStatistics> fig;  // one a figure, over the runs that have it
  std::string regime;                 // "bubbling (2 of 2)"
  std::vector<std::string> moves;     // the figures it moves beyond two standard errors
  int failed = 0;
};

struct Measured {
  std::string scene_path, command;
  std::vector<Variation> variations;
  std::vector<std::uint64_t> seeds;
  double until = 0.0, averaging = 0.0;
  std::vector<Figure> figs;
  std::vector<Point> pts;
};

// Does P move figure K beyond two standard errors of the difference from the base? -1: cannot
// tell (fewer than two runs on a side).
int moves(const SampleStatistics& p, const SampleStatistics& b) {
  if (p.n < 2 || b.n < 2 || !std::isfinite(p.mean) || !std::isfinite(b.mean)) return -1;
  const double se = std::sqrt(p.std * p.std / p.n + b.std * b.std / b.n);
  const double diff = std::fabs(p.mean - b.mean);
  return se > 0.0 ? diff > 2.0 * se : diff > 0.0;
}

std::string regime_words(const std::vector<PointRun>& runs) {
  std::map<std::string, int> count;
  int n = 0;
  for (const PointRun& r : runs) {
    if (!r.ok) continue;
    const nlohmann::json& s = r.result.summary;
    const bool has = s.contains("bubbles") && s["bubbles"].contains("regime") &&
                     s["bubbles"]["regime"].is_string();
    ++count[has ? s["bubbles"]["regime"].get<std::string>() : std::string("?")];
    ++n;
  }
  std::string w;
  for (const auto& [name, c] : count)
    w += (w.empty() ? "" : ", ") + name + " (" + std::to_string(c) + " of " + std::to_string(n) + ")";
  return w;
}

Measured measure(const Options& o) {
  const Options::SceneStudy& a = o.scene_study;
  Measured m;
  m.scene_path = a.scene;
  const Settings base = load_scene(a.scene, a.overrides);
  for (const std::string& v : a.vary) m.variations.push_back(parse_variation(v));
  m.until = a.until > 0.0 ? a.until : base.time.end;
  m.averaging = base.diagnostics.averaging_start;
  m.seeds = {lattice_seed(base)};
  if (!a.seeds.empty()) {
    check_seeded_start(base);
    m.seeds = parse_seeds(a.seeds, m.seeds[0]);
  }
  m.figs = figures(base.diagnostics.probes.size(), m.until);
  // Every point's scene first: a refused value stops the study before any run.
  for (SensitivityPoint& p : sensitivity_points(base, m.variations)) {
    Point pt;
    std::vector<std::string> all = a.overrides;
    all.insert(all.end(), p.overrides.begin(), p.overrides.end());
    try {
      pt.scene = load_scene(a.scene, all);
    } catch (const InputError& e) {
      throw InputError("study sensitivity: " + p.label + ": " + e.what());
    }
    pt.def = std::move(p);
    m.pts.push_back(std::move(pt));
  }
  if (!o.out.empty()) {
    fs::create_directories(fs::path(o.out) / "scenes");
    for (std::size_t i = 0; i < m.pts.size(); ++i)
      write_text((fs::path(o.out) / "scenes" / fmt("%02.0f.toml", static_cast<double>(i))).string(),
                 "# " + m.pts[i].def.label + "\n" + to_toml(m.pts[i].scene));
  }
  // The runs: every point at every seed, each on one thread; their packed beds first, each
  // distinct packing once (a grid or a seed of its own packs anew; the inlet does not).
  struct Run {
    std::size_t point;
    Settings s;
  };
  std::vector<Run> runs;
  for (std::size_t i = 0; i < m.pts.size(); ++i)
    for (std::uint64_t seed : m.seeds) {
      Settings s = m.seeds.size() > 1 ? with_seed(m.pts[i].scene, seed) : m.pts[i].scene;
      s.threads = 1;
      runs.push_back({i, std::move(s)});
    }
  std::map<std::string, Settings> packings;
  for (const Run& r : runs)
    if (r.s.particles.placement == Placement::Packed)
      packings.emplace(to_toml(packing_settings_for(r.s)), r.s);
  std::vector<Settings> to_pack;
  for (auto& [key, s] : packings) to_pack.push_back(s);
  if (o.log && !to_pack.empty())
    o.log(std::to_string(to_pack.size()) + " packed bed(s), cached after the first time");
  RunPool(o.workers).map<int>(to_pack.size(), [&](std::size_t k) {
    stop_if_asked(o);
    packed_bed_state(to_pack[k], o.log);
    return 0;
  });
  for (Run& r : runs) prepare_packed_bed(r.s);
  const std::vector<PointRun> done = RunPool(o.workers).map<PointRun>(runs.size(), [&](std::size_t k) {
    PointRun p = run_point(o, runs[k].s, m.until, /*bubbles=*/true);
    if (o.log)
      o.log("  " + m.pts[runs[k].point].def.label + fmt(", seed %.0f", static_cast<double>(
                                                         lattice_seed(runs[k].s))) +
            (p.ok ? fmt(": dp %.0f Pa", json_number(p.result.summary, "dp_mean_pa")) +
                        fmt(", cost %.3g CPU s/s", p.cpu / m.until)
                  : ": failed: " + p.error));
    return p;
  });
  for (std::size_t k = 0; k < runs.size(); ++k) {
    Point& pt = m.pts[runs[k].point];
    pt.runs.push_back(done[k]);
    pt.failed += done[k].ok ? 0 : 1;
  }
  for (Point& pt : m.pts) {
    for (const Figure& f : m.figs) {
      std::vector<double> v;
      for (const PointRun& r : pt.runs) {
        if (!r.ok) continue;
        if (const double x = f.of(r); std::isfinite(x)) v.push_back(x);
      }
      pt.fig.push_back(sample_statistics(v));
    }
    pt.regime = regime_words(pt.runs);
  }
  for (Point& pt : m.pts)
    for (std::size_t k = 0; k < m.figs.size(); ++k)
      if (&pt != &m.pts[0] && moves(pt.fig[k], m.pts[0].fig[k]) == 1)
        pt.moves.push_back(m.figs[k].column);
  return m;
}

Table table(const Measured& m) {
  std::vector<std::string> cols = {"point", "keys", "values", "held", "runs", "failed", "regime"};
  for (const Figure& f : m.figs)
    for (const char* s : {"", "_std", "_n"}) cols.push_back(f.column + s);
  cols.push_back("moves");
  cols.push_back("failure");
  Table t(cols);
  for (const Point& p : m.pts) {
    std::string keys, values, moved, failure;
    if (p.def.variation >= 0) {
      const Variation& v = m.variations[static_cast<std::size_t>(p.def.variation)];
      for (std::size_t k = 0; k < v.keys.size(); ++k) {
        keys += (k ? " " : "") + v.keys[k];
        values += (k ? " " : "") + v.values[p.def.value][k];
      }
    }
    for (const std::string& c : p.moves) moved += (moved.empty() ? "" : " ") + c;
    for (const PointRun& r : p.runs)
      if (!r.ok && failure.empty()) failure = r.error;
    std::vector<std::string> row = {p.def.label, keys, values, p.def.held,
                                    std::to_string(p.runs.size()), std::to_string(p.failed),
                                    p.regime};
    for (const SampleStatistics& s : p.fig) {
      row.push_back(num(s.mean));
      row.push_back(num(s.std));
      row.push_back(std::to_string(s.n));
    }
    row.push_back(moved);
    row.push_back(failure);
    t.add(row, p.failed == static_cast<int>(p.runs.size()));
  }
  return t;
}

// runs.csv: every run, its seed and figures.
void write_runs(const Measured& m, const std::string& dir) {
  std::vector<std::string> cols = {"point", "seed", "status", "failure_kind", "failure", "wall_s"};
  for (const Figure& f : m.figs) cols.push_back(f.column);
  Table t(cols);
  for (const Point& p : m.pts)
    for (std::size_t k = 0; k < p.runs.size(); ++k) {
      const PointRun& r = p.runs[k];
      std::vector<std::string> row = {p.def.label, std::to_string(m.seeds[k]),
                                      r.ok ? "ok" : "failed", r.kind, r.error, num(r.wall)};
      for (const Figure& f : m.figs) row.push_back(num(r.ok ? f.of(r) : NAN));
      t.add(row);
    }
  write_text((fs::path(dir) / "runs.csv").string(), t.csv());
}

// The number of a value of the variation's first key, or NaN when it is not one.
double as_number(const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  return end && *end == '\0' && end != v.c_str() ? x : NAN;
}

// The charts, one a variation, and runs.csv beside them (the runs behind every mean).
std::vector<std::string> charts(const Measured& m, const std::string& dir) {
  if (!dir.empty()) write_runs(m, dir);
  std::vector<std::string> files;
  const Point& base = m.pts[0];
  for (std::size_t v = 0; v < m.variations.size(); ++v) {
    const Variation& var = m.variations[v];
    // x: the first key's value where every value is a number, else the value's place.
    bool numeric = true;
    for (const auto& t : var.values) numeric = numeric && std::isfinite(as_number(t[0]));
    std::string keys;
    for (const std::string& k : var.keys) keys += (keys.empty() ? "" : ", ") + k;
    std::vector<chart::Chart> panels;
    for (std::size_t k = 0; k < m.figs.size(); ++k) {
      if (!m.figs[k].chart) continue;
      chart::Chart c;
      c.title = m.figs[k].heading;
      c.x.label = numeric ? var.keys[0] : keys + " (value in turn)";
      c.y.label = m.figs[k].heading;
      c.legend = false;
      // The points in the order of x, the base among them where its value is a number.
      struct At {
        double x;
        const SampleStatistics* f;
        std::string label;
      };
      std::vector<At> at;
      for (const Point& p : m.pts) {
        if (p.def.variation != static_cast<int>(v)) continue;
        std::string label;
        for (const std::string& x : var.values[p.def.value]) label += (label.empty() ? "" : ":") + x;
        const double x = numeric ? as_number(var.values[p.def.value][0])
                                 : static_cast<double>(p.def.value + 1);
        at.push_back({x, &p.fig[k], label});
      }
      const double bx = as_number(scene_value(base.scene, var.keys[0]));
      if (numeric && std::isfinite(bx)) at.push_back({bx, &base.fig[k], "base"});
      std::stable_sort(at.begin(), at.end(), [](const At& a, const At& b) { return a.x < b.x; });
      chart::Series s;
      s.mark = chart::Mark::LinePoints;
      for (const At& a : at) {
        s.x.push_back(a.x);
        s.y.push_back(a.f->mean);
        s.y_error.push_back(std::isfinite(a.f->std) ? a.f->std : 0.0);
        s.point_labels.push_back(a.label);
      }
      c.series.push_back(s);
      const SampleStatistics& b = base.fig[k];
      if (std::isfinite(b.mean)) {
        c.hlines.push_back({b.mean, "base", {60, 60, 60}, false, 1.5});
        if (std::isfinite(b.std) && b.std > 0.0) {
          c.hlines.push_back({b.mean + b.std, "+1 sd", {150, 150, 150}, true, 1.0});
          c.hlines.push_back({b.mean - b.std, "-1 sd", {150, 150, 150}, true, 1.0});
        }
      }
      panels.push_back(std::move(c));
    }
    if (dir.empty() || panels.empty()) continue;
    std::string file = "vary";
    for (const std::string& k : var.keys) file += "-" + k;
    std::replace(file.begin(), file.end(), '.', '_');
    files.push_back(write_grid(dir, file + ".png", panels, 4, 560, 380,
                               "Figures against " + keys + " (base: line, its spread over packings: "
                               "dashed; error bars: one standard deviation)"));
  }
  return files;
}

std::string figure_text(const SampleStatistics& s) {
  if (!std::isfinite(s.mean)) return "-";
  return fmt("%.4g", s.mean) + (std::isfinite(s.std) ? fmt(" +- %.2g", s.std) : "");
}

std::string findings(const Measured& m) {
  std::ostringstream md;
  md << "Scene `" << m.scene_path << "`, " << m.until << " s a run, figures from "
     << m.averaging << " s; " << m.seeds.size() << " packing(s) a point (lattice seeds";
  for (std::uint64_t s : m.seeds) md << " " << s;
  md << "), every run on one thread. A figure is the mean over the point's runs +- their "
        "standard deviation (n - 1). The probes' pressures are against the outlet, their spread "
        "the standard deviation after start-up; a regular cycle is the share of runs whose "
        "verdict says so (analysis/cycles.hpp). Cost: CPU seconds per simulated second.\n\n";
  md << "| point | held fixed | regime |";
  std::vector<std::size_t> shown;
  for (std::size_t k = 0; k < m.figs.size(); ++k)
    if (m.figs[k].chart) {
      shown.push_back(k);
      md << " " << m.figs[k].heading << " |";
    }
  md << "\n|---|---|---|";
  for (std::size_t k = 0; k < shown.size(); ++k) md << "---|";
  md << "\n";
  for (const Point& p : m.pts) {
    md << "| " << p.def.label << " | " << (p.def.held.empty() ? "-" : p.def.held) << " | "
       << (p.regime.empty() ? "failed" : p.regime) << " |";
    for (std::size_t k : shown) md << " " << figure_text(p.fig[k]) << " |";
    md << "\n";
  }
  md << "\n**Which keys move which figures** (beyond two standard errors of the difference "
        "from the base, the studies' settled rule; cannot tell: fewer than two runs with the figure on a side):\n\n"
     << "| varied | moves | does not move | cannot tell |\n|---|---|---|---|\n";
  for (std::size_t v = 0; v < m.variations.size(); ++v) {
    std::string yes, no, unknown_list;
    for (std::size_t k = 0; k < m.figs.size(); ++k) {
      bool moved = false, unknown = false;
      for (const Point& p : m.pts) {
        if (p.def.variation != static_cast<int>(v)) continue;
        const int r = moves(p.fig[k], m.pts[0].fig[k]);
        moved = moved || r == 1;
        unknown = unknown || r == -1;
      }
      std::string& into = moved ? yes : unknown ? unknown_list : no;
      into += (into.empty() ? "" : ", ") + m.figs[k].column;
    }
    md << "| `" << m.variations[v].text << "` | " << (yes.empty() ? "-" : yes) << " | "
       << (no.empty() ? "-" : no) << " | " << (unknown_list.empty() ? "-" : unknown_list)
       << " |\n";
  }
  return md.str();
}

std::string advice(const Measured& m) {
  std::ostringstream adv;
  std::vector<std::string> deciding;
  for (std::size_t v = 0; v < m.variations.size(); ++v) {
    for (const Point& p : m.pts)
      if (p.def.variation == static_cast<int>(v) && !p.moves.empty()) {
        deciding.push_back("`" + m.variations[v].text + "`");
        break;
      }
  }
  if (m.seeds.size() < 2) {
    adv << "One packing a point: a difference cannot be told from the packing's own spread, so "
           "no key is named as deciding. Run again with `--seeds 3` (or more) for the rule.";
  } else if (deciding.empty()) {
    adv << "No varied key moves a figure beyond two standard errors over " << m.seeds.size()
        << " packings: at this spread the settings varied here do not decide the figures.";
  } else {
    adv << "Over " << m.seeds.size() << " packings, these variations move at least one figure "
        << "beyond two standard errors: ";
    for (std::size_t i = 0; i < deciding.size(); ++i) adv << (i ? ", " : "") << deciding[i];
    adv << ". Choose those with care (converge a numerical one, source a physical one); the "
           "others do not matter at this spread.";
  }
  return adv.str();
}

}  // namespace

Report sensitivity_study(const Options& o) {
  if (o.scene_study.scene.empty() || o.scene_study.vary.empty())
    throw InputError("study sensitivity: needs --scene SCENE.toml and at least one --vary");
  return run_steps<Measured>(o, {measure, table, charts, findings, advice});
}

}  // namespace fluidbed::app::study
