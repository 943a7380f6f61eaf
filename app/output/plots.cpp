#include "output/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "chart/chart.hpp"
#include "render/asset_dir.hpp"
#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "core/steps.hpp"

namespace fluidbed::app {
namespace {

const chart::Font& font() {
  static const chart::Font f = chart::Font::load_default(render::asset_dir());
  return f;
}

// One quantity of a run against time, a thin line, no legend (Figs 8 and 15).
chart::Chart against_time(const std::string& title, const std::string& y_label,
                          const std::vector<double>& t, const std::vector<double>& y) {
  chart::Chart c;
  c.title = title;
  c.x.label = "time (s)";
  c.y.label = y_label;
  c.legend = false;
  chart::Series s;
  s.x = t;
  s.y = y;
  s.width = 1.2;
  c.series = {s};
  return c;
}

// The sheets of one run (dp.png, overlap.png) are 1200 x 600 px: text and lines at 1.2 times
// the sizes of an 800 x 500 chart (chart/chart.hpp). Figures of several panels use the same.
constexpr int kSheetW = 1200, kSheetH = 600;  // px
constexpr double kSheetScale = 1.2;

// Where the particles went (m): the extent of every track with a margin of 5 % of the larger
// span (at least 2 mm), kept inside the bed.
struct Extent {
  double x0, x1, y0, y1;
};
Extent track_extent(const std::vector<Trajectory>& tracks, double width, double height) {
  Extent e{INFINITY, -INFINITY, INFINITY, -INFINITY};
  for (const auto& tr : tracks)
    for (std::size_t k = 0; k < tr.x.size(); ++k) {
      e.x0 = std::min(e.x0, tr.x[k]);
      e.x1 = std::max(e.x1, tr.x[k]);
      e.y0 = std::min(e.y0, tr.y[k]);
      e.y1 = std::max(e.y1, tr.y[k]);
    }
  if (!(e.x0 <= e.x1) || !(e.y0 <= e.y1)) return {0.0, width, 0.0, height};  // nothing recorded
  const double pad = std::max(0.002, 0.05 * std::max(e.x1 - e.x0, e.y1 - e.y0));
  return {std::max(0.0, e.x0 - pad), std::min(width, e.x1 + pad), std::max(0.0, e.y0 - pad),
          std::min(height, e.y1 + pad)};
}

// Figs 12-13: the paths in the bed at true aspect, cropped to where the particles went, beside
// x and y against time stacked on one time axis. The path panel is as wide as its content needs
// at the sheet's height, so the sheet has no empty band, and every panel's text is the size of
// the run's other charts.
chart::Image trajectory_figure(const std::vector<Trajectory>& tracks, double width,
                               double height) {
  chart::Chart path, xs, ys;
  path.title = "Tracked particle paths (Fig. 12)";
  path.x.label = "x (m)";
  path.y.label = "y (m)";
  const Extent e = track_extent(tracks, width, height);
  path.x.min = e.x0;
  path.x.max = e.x1;
  path.y.min = e.y0;
  path.y.max = e.y1;
  path.legend = false;  // the time panels beside it name the particles, in the same colours
  xs.title = "x against time (Fig. 13)";
  xs.x.label = "time (s)";
  xs.y.label = "x (m)";
  ys.title = "y against time (Fig. 13)";
  ys.x.label = "time (s)";
  ys.y.label = "y (m)";
  for (const auto& tr : tracks) {
    const std::string label = "particle " + std::to_string(tr.id);
    chart::Series a;
    a.label = label;
    a.x = tr.x;
    a.y = tr.y;
    a.width = 1.2;
    path.series.push_back(a);
    chart::Series b = a;
    b.x = tr.t;
    b.y = tr.x;
    xs.series.push_back(b);
    chart::Series c = a;
    c.x = tr.t;
    c.y = tr.y;
    ys.series.push_back(c);
  }
  // The path panel's width: its margins (laid out once at a trial width) plus the plot's height
  // times the aspect of the region shown; at least its title's width, at most a sheet's.
  const int h = 2 * kSheetH;
  const chart::Layout trial = chart::layout(path, kSheetW, h, font(), kSheetScale);
  const double margins = trial.plot.x0 + (kSheetW - trial.plot.x1);
  const double aspect = (e.x1 - e.x0) / (e.y1 - e.y0);
  const double least = trial.title.width() + 2.0 * 12.0 * kSheetScale;  // the chart's padding
  const int w = static_cast<int>(std::lround(
      std::clamp(margins + trial.plot.height() * aspect, least, static_cast<double>(kSheetW))));
  path.equal_aspect = true;  // a metre as long across as up; the box shrinks where it must
  return chart::render_figure({{path, 0, 0, w, h},
                               {xs, w, 0, kSheetW, kSheetH},
                               {ys, w, kSheetH, kSheetW, kSheetH}},
                              kSheetScale, font(), "Particles starting in the jet region");
}

}  // namespace

std::vector<int> nearest_particles(const DemSolver& dem,
                                   const std::vector<std::pair<double, double>>& at) {
  const Particles& p = dem.particles();
  std::vector<int> ids;
  for (const auto& [x, y] : at) {
    int best = 0;
    double d2 = INFINITY;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double d = (p.x[i] - x) * (p.x[i] - x) + (p.y[i] - y) * (p.y[i] - y);
      if (d < d2) {
        d2 = d;
        best = static_cast<int>(i);
      }
    }
    ids.push_back(static_cast<int>(dem.id_of(static_cast<std::size_t>(best))));
  }
  return ids;
}

std::vector<std::pair<double, double>> jet_region_points(double width) {
  return {{0.5 * width, 0.02}, {0.5 * width, 0.06}};
}

TrajectoryRecorder::TrajectoryRecorder(const std::vector<int>& ids, double interval, double dt)
    : every_(std::max<std::int64_t>(1, steps_for(interval, dt))) {
  for (int id : ids) tracks_.push_back({id, {}, {}, {}});
}

void TrajectoryRecorder::observe(const Simulation& sim) {
  if (sim.steps() % every_ != 0) return;
  const Particles& p = sim.dem().particles();
  for (auto& tr : tracks_) {
    tr.t.push_back(sim.time());
    const std::size_t at = sim.dem().place_of(static_cast<std::size_t>(tr.id));
    tr.x.push_back(p.x[at]);
    tr.y.push_back(p.y[at]);
  }
}

void TrajectoryRecorder::save(BinarySink& out) const { out(every_, tracks_); }

void TrajectoryRecorder::restore(BinarySource& in, std::size_t particles) {
  const std::int64_t every = every_;
  const std::size_t count = tracks_.size();
  in(every_, tracks_);
  if (every_ != every) in.fail("inconsistent (trajectory interval)");
  if (tracks_.size() != count) in.fail("inconsistent (tracked particles)");
  for (const Trajectory& tr : tracks_)
    if (tr.id < 0 || static_cast<std::size_t>(tr.id) >= particles || tr.x.size() != tr.t.size() ||
        tr.y.size() != tr.t.size())
      in.fail("inconsistent (tracked particle)");
}

void save_tracks(const std::string& folder, const TrajectoryRecorder& r) {
  const std::string p = (std::filesystem::path(folder) / "tracks.bin").string();
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  BinarySink sink(f);
  r.save(sink);
  f.flush();
  if (!f) throw InputError("cannot write " + p);
}

void restore_tracks(const std::string& folder, TrajectoryRecorder& r, std::size_t particles) {
  const std::string p = (std::filesystem::path(folder) / "tracks.bin").string();
  std::ifstream in = open_input_file(p, "checkpoint trajectories");
  BinarySource src(in, p);
  r.restore(src, particles);
}

void plot_sweep(const std::string& path, const SweepResult& r, const std::string& scene) {
  chart::Chart c;
  c.title = "Bed pressure drop against superficial gas velocity (" + scene + ")";
  c.x.label = "superficial gas velocity U (m/s)";
  c.y.label = "mean bed pressure drop (Pa)";
  c.x.min = 0.0;
  c.y.min = 0.0;
  auto branch = [](const std::vector<SweepPoint>& pts, const char* label) {
    chart::Series s;
    s.label = label;
    s.mark = chart::Mark::LinePoints;
    for (const auto& p : pts) {
      if (!p.ok) continue;
      s.x.push_back(p.u);
      s.y.push_back(p.dp_mean);
      s.y_error.push_back(p.dp_std);
    }
    return s;
  };
  chart::Series up = branch(r.up, "increasing U (from the packed bed)");
  std::vector<SweepPoint> down = r.down;
  for (auto it = r.up.rbegin(); it != r.up.rend(); ++it)
    if (it->ok) {  // the shared top run, where the decreasing branch starts, closes it
      down.push_back(*it);
      break;
    }
  chart::Series dn = branch(down, "decreasing U (from the run above)");
  dn.dashed = true;
  dn.filled = false;
  dn.shape = chart::Shape::Square;
  c.series = {up, dn};
  chart::Series failed;  // runs that failed, on the axis (sweep.csv gives each one's reason)
  failed.label = "failed run (sweep.csv: why)";
  failed.mark = chart::Mark::Points;
  failed.shape = chart::Shape::Triangle;
  failed.colour = chart::Rgb{200, 30, 30};
  for (const auto* branch_points : {&r.up, &r.down})
    for (const auto& p : *branch_points)
      if (!p.ok && p.error.rfind("not run", 0) != 0) {
        failed.x.push_back(p.u);
        failed.y.push_back(0.0);
      }
  if (!failed.x.empty()) c.series.push_back(failed);
  c.hlines.push_back({r.bed_weight_per_area, "bed weight / area", {90, 90, 90}, true, 1.5});
  if (r.umf.ok) {
    char label[64];
    std::snprintf(label, sizeof label, "Umf = %.2f m/s", r.umf.umf);
    c.vlines.push_back({r.umf.umf, label, chart::palette(1), true, 1.5});
  }
  chart::render(c, 1200, 750, font()).write_png(path);
}

namespace {

// Mean of dp over the seeds at each velocity of one branch (the runs that finished).
chart::Series branch_mean(const std::vector<const std::vector<SweepPoint>*>& branches,
                          const std::string& label) {
  std::vector<std::pair<double, std::pair<double, int>>> acc;  // u -> (sum, n)
  for (const auto* pts : branches)
    for (const auto& p : *pts) {
      if (!p.ok) continue;
      auto it = std::find_if(acc.begin(), acc.end(), [&](const auto& a) { return a.first == p.u; });
      if (it == acc.end()) {
        acc.push_back({p.u, {p.dp_mean, 1}});
      } else {
        it->second.first += p.dp_mean;
        ++it->second.second;
      }
    }
  std::sort(acc.begin(), acc.end());
  chart::Series s;
  s.label = label;
  s.mark = chart::Mark::LinePoints;
  s.width = 3.0;
  for (const auto& a : acc) {
    s.x.push_back(a.first);
    s.y.push_back(a.second.first / a.second.second);
  }
  return s;
}

// The decreasing branch with the shared top run, where it starts.
std::vector<SweepPoint> closed_down(const SweepResult& r) {
  std::vector<SweepPoint> down = r.down;
  for (auto it = r.up.rbegin(); it != r.up.rend(); ++it)
    if (it->ok) {
      down.push_back(*it);
      break;
    }
  return down;
}

}  // namespace

void plot_sweep_ensemble(const std::string& path, const std::vector<SweepResult>& members,
                         const nlohmann::json& umf_stats, const std::string& scene) {
  chart::Chart c;
  c.title = "Bed pressure drop against superficial gas velocity (" + scene + ", " +
            std::to_string(members.size()) + " packings)";
  c.x.label = "superficial gas velocity U (m/s)";
  c.y.label = "mean bed pressure drop (Pa)";
  c.x.min = 0.0;
  c.y.min = 0.0;
  // Each branch in one colour: bold for the mean, 35 % of it on white for each packing.
  const chart::Rgb bold_up = chart::palette(0), bold_down = chart::palette(1);
  auto faint = [](chart::Rgb colour) {
    auto mix = [](std::uint8_t v) { return static_cast<std::uint8_t>(255 - (255 - v) * 35 / 100); };
    return chart::Rgb{mix(colour.r), mix(colour.g), mix(colour.b)};
  };
  const chart::Rgb faint_up = faint(bold_up), faint_down = faint(bold_down);
  const chart::Rgb umf_colour = chart::palette(2);
  std::vector<std::vector<SweepPoint>> downs;
  for (const auto& m : members) downs.push_back(closed_down(m));
  for (std::size_t k = 0; k < members.size(); ++k) {
    for (int b = 0; b < 2; ++b) {
      chart::Series s;
      s.mark = chart::Mark::Line;
      s.width = 1.0;
      s.colour = b == 0 ? faint_up : faint_down;
      s.dashed = b == 1;
      if (k == 0) s.label = b == 0 ? "each packing, increasing" : "each packing, decreasing";
      for (const auto& p : b == 0 ? members[k].up : downs[k])
        if (p.ok) {
          s.x.push_back(p.u);
          s.y.push_back(p.dp_mean);
        }
      c.series.push_back(std::move(s));
    }
  }
  std::vector<const std::vector<SweepPoint>*> ups, dns;
  for (std::size_t k = 0; k < members.size(); ++k) {
    ups.push_back(&members[k].up);
    dns.push_back(&downs[k]);
  }
  chart::Series up = branch_mean(ups, "increasing U, mean over the packings");
  up.colour = bold_up;
  chart::Series dn = branch_mean(dns, "decreasing U, mean over the packings");
  dn.colour = bold_down;
  dn.dashed = true;
  dn.filled = false;
  dn.shape = chart::Shape::Square;
  c.series.push_back(up);
  c.series.push_back(dn);
  if (!members.empty())
    c.hlines.push_back(
        {members.front().bed_weight_per_area, "bed weight / area", {90, 90, 90}, true, 1.5});
  if (umf_stats.is_object() && umf_stats.contains("mean")) {
    const double mean = umf_stats["mean"].get<double>();
    char label[96];
    if (umf_stats["std"].is_number()) {
      const double sd = umf_stats["std"].get<double>();
      std::snprintf(label, sizeof label, "Umf = %.2f +- %.2f m/s", mean, sd);
      c.vlines.push_back({mean - sd, "", umf_colour, true, 1.0});
      c.vlines.push_back({mean + sd, "", umf_colour, true, 1.0});
    } else {
      std::snprintf(label, sizeof label, "Umf = %.2f m/s (one packing)", mean);
    }
    c.vlines.push_back({mean, label, umf_colour, false, 2.5});
  }
  chart::render(c, 1200, 750, font()).write_png(path);
}

void plot_dp_ensemble(const std::string& path, const std::vector<SeedTrace>& traces,
                      double bed_weight_per_area, const std::string& scene) {
  chart::Chart c;
  c.title = "Bed pressure drop against time (" + scene + ", " + std::to_string(traces.size()) +
            " packings)";
  c.x.label = "time (s)";
  c.y.label = "pressure drop (Pa)";
  for (std::size_t k = 0; k < traces.size(); ++k) {
    chart::Series s;
    s.label = "seed " + std::to_string(traces[k].seed);
    s.x = traces[k].t;
    s.y = traces[k].dp;
    s.width = 1.0;
    s.colour = chart::palette(k);
    c.series.push_back(std::move(s));
  }
  c.hlines.push_back({bed_weight_per_area, "bed weight / area", {90, 90, 90}, true, 1.5});
  chart::render(c, kSheetW, kSheetH, font()).write_png(path);
}

namespace {

// A spectrum up to 20 Hz as a line (the mean, 0 Hz, is removed).
chart::Series spectrum_series(const PowerSpectrum& sp, std::string label) {
  chart::Series s;
  s.label = std::move(label);
  for (std::size_t k = 1; k < sp.frequency.size(); ++k) {
    if (sp.frequency[k] > 20.0) break;
    s.x.push_back(sp.frequency[k]);
    s.y.push_back(sp.psd[k]);
  }
  return s;
}

// Welch's power spectrum of dp (log scale), its dominant frequency marked, and each probe's
// beside it (their colours after the marker's).
chart::Image spectrum_chart(const PowerSpectrum& sp, const std::vector<ProbePoint>& probes,
                            const std::vector<PowerSpectrum>& probe_spectra) {
  chart::Chart c;
  c.title = probes.empty()
                ? "Power spectrum of the pressure drop after start-up (Welch)"
                : "Power spectra of the pressure drop and the probes after start-up (Welch)";
  c.x.label = "frequency (Hz)";
  c.y.label = "power spectral density (Pa^2/Hz)";
  c.y.log = true;
  c.series.push_back(spectrum_series(sp, "pressure drop"));
  c.series.back().colour = chart::palette(0);
  for (std::size_t k = 0; k < probe_spectra.size() && k < probes.size(); ++k) {
    if (!probe_spectra[k].ok) continue;
    char label[96];
    std::snprintf(label, sizeof label, "probe %zu at (%g, %g) m", k + 1, probes[k].x, probes[k].y);
    chart::Series s = spectrum_series(probe_spectra[k], label);
    s.colour = chart::palette(k + 2);
    s.width = 1.5;
    c.series.push_back(std::move(s));
  }
  c.legend = c.series.size() > 1;
  if (sp.dominant_frequency_refined > 0.0) {
    char label[64];
    std::snprintf(label, sizeof label, "%sdominant %.2f Hz", probes.empty() ? "" : "dp ",
                  sp.dominant_frequency_refined);
    c.vlines.push_back({sp.dominant_frequency_refined, label, chart::palette(1), true, 1.5});
  }
  return chart::render(c, 1200, 600, font());
}

// Bubbles after start-up: equivalent diameter against height, and rise velocity against
// diameter beside the two-dimensional relation u_b = 0.5 sqrt(g D_e) (Pyle and Harrison), drawn
// as a reference, not a fit.
chart::Image bubble_figure(const std::vector<BubbleRow>& rows, double start) {
  chart::Chart size;
  size.title = "Bubble size against height";
  size.x.label = "height of the centroid (m)";
  size.y.label = "equivalent diameter (mm)";
  chart::Series pts;
  pts.mark = chart::Mark::Points;
  pts.marker_size = 4.0;
  chart::Chart rise;
  rise.title = "Rise velocity against size";
  rise.x.label = "equivalent diameter (mm)";
  rise.y.label = "rise velocity (m/s)";
  chart::Series vel = pts;
  vel.label = "bubbles";
  double dmax = 0.0;
  for (const BubbleRow& b : rows) {
    if (b.t <= start || b.event == BubbleEvent::erupted || b.event == BubbleEvent::vanished) continue;
    pts.x.push_back(b.y);
    pts.y.push_back(1e3 * b.d_eq);
    if (b.has_velocity) {
      vel.x.push_back(1e3 * b.d_eq);
      vel.y.push_back(b.vy);
      dmax = std::max(dmax, b.d_eq);
    }
  }
  size.series.push_back(std::move(pts));
  size.legend = false;
  rise.series.push_back(std::move(vel));
  chart::Series ref;
  ref.label = "u_b = 0.5 sqrt(g D_e) (2D, Pyle & Harrison)";
  ref.dashed = true;
  for (int k = 0; k <= 50 && dmax > 0.0; ++k) {
    const double d = dmax * k / 50.0;
    ref.x.push_back(1e3 * d);
    ref.y.push_back(0.5 * std::sqrt(9.81 * d));
  }
  rise.series.push_back(std::move(ref));
  return chart::render_grid({size, rise}, 2, 900, 600, font(),
                            "Bubbles after start-up (bubbles.csv)");
}

// Lacey's mixing index of the lower and upper halves of the bed (by initial height).
chart::Image mixing_chart(const std::vector<MixingSample>& m) {
  std::vector<double> t, index;
  for (const MixingSample& s : m) {
    t.push_back(s.t);
    index.push_back(s.index);
  }
  chart::Chart c = against_time("Mixing of the lower and upper halves of the bed (Lacey index)",
                                "Lacey index M (0 segregated, 1 random)", t, index);
  c.y.min = 0.0;
  c.y.max = 1.1;
  c.hlines.push_back({1.0, "random", {150, 150, 150}, true, 1.0});
  return chart::render(c, 1200, 600, font());
}

}  // namespace

std::vector<std::string> plot_run(const std::string& dir, const RunResult& r,
                                  const std::vector<Trajectory>& tracks, double width,
                                  double height, bool has_gas) {
  namespace fs = std::filesystem;
  std::vector<std::string> written;
  std::vector<double> t, dp, overlap;
  for (const auto& row : r.rows) {
    t.push_back(row.t);
    dp.push_back(row.dp);
    overlap.push_back(100.0 * row.max_overlap_ratio);
  }
  const double start = r.summary.value("averaging_start_s", 0.0);
  if (has_gas) {
    chart::Chart c = against_time("Bed pressure drop against time (Fig. 8)", "pressure drop (Pa)",
                                  t, dp);
    c.hlines.push_back({r.summary.value("bed_weight_per_area_pa", 0.0), "bed weight / area",
                        {90, 90, 90}, true, 1.5});
    if (r.summary.contains("dp_mean_pa") && r.summary["dp_mean_pa"].is_number())
      c.hlines.push_back({r.summary["dp_mean_pa"].get<double>(), "mean after start-up (eq 30)",
                          chart::palette(1), true, 1.5});
    c.vlines.push_back({start, "averaging start", {150, 150, 150}, true, 1.0});
    const auto p = (fs::path(dir) / "dp.png").string();
    chart::render(c, 1200, 600, font()).write_png(p);
    written.push_back(p);
  }
  {
    chart::Chart c = against_time("Maximum overlap ratio against time (Fig. 15)",
                                  "max overlap ratio (%)", t, overlap);
    c.y.min = 0.0;
    c.hlines.push_back({1.0, "1 %", {150, 150, 150}, true, 1.0});
    const auto p = (fs::path(dir) / "overlap.png").string();
    chart::render(c, 1200, 600, font()).write_png(p);
    written.push_back(p);
  }
  if (r.dp_spectrum.ok) {
    const auto p = (fs::path(dir) / "dp_spectrum.png").string();
    spectrum_chart(r.dp_spectrum, r.probes, r.probe_spectra).write_png(p);
    written.push_back(p);
  }
  if (r.bubbles) {
    const auto p = (fs::path(dir) / "bubbles.png").string();
    bubble_figure(r.bubble_rows, r.summary.value("averaging_start_s", 0.0)).write_png(p);
    written.push_back(p);
    const auto m = (fs::path(dir) / "mixing.png").string();
    mixing_chart(r.mixing).write_png(m);
    written.push_back(m);
  }
  if (!tracks.empty()) {
    const auto p = (fs::path(dir) / "trajectory.png").string();
    trajectory_figure(tracks, width, height).write_png(p);
    written.push_back(p);
  }
  return written;
}

}  // namespace fluidbed::app
