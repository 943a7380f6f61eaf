// The report of `fluidbed reproduce` (cli/paper_report.hpp): every figure of the paper that the
// runs measured, beside the paper's value, as markdown.
#include "cli/paper_report.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

#include "analysis/spectrum.hpp"
#include "core/text_format.hpp"
#include "core/threads.hpp"
#include "run/ensemble.hpp"

namespace fluidbed::app {
namespace {

// One number into its printf format; "n/a" for a value the run could not measure (no bubble
// tracked, no spectrum).
std::string fmt(const char* f, double v) {
  return format_number(f, v, "n/a");
}

using study::json_number;
double num(const nlohmann::json& j, const char* key) {
  return json_number(j, key);
}
double num(const nlohmann::json& j, const char* object, const char* key) {
  return json_number(j, object, key);
}

std::string text(const nlohmann::json& j, const char* object, const char* key) {
  return j.contains(object) && j[object].contains(key) && j[object][key].is_string()
             ? j[object][key].get<std::string>()
             : "n/a";
}

// The report's bubble rows of one run (the bubble analysis of model.md section 6).
void bubble_rows(std::ostringstream& md, const char* run, const nlohmann::json& j) {
  const double d = num(j, "bubbles", "mean_d_eq_m");
  const double rise = num(j, "bubbles", "mean_rise_velocity_m_s");
  const double ref = num(j, "bubbles", "mean_rise_velocity_2d_ref_m_s");
  const double erupt = num(j, "bubbles", "eruptions_per_s");
  const double f = num(j, "dp_spectrum", "dominant_frequency_hz");
  md << "| " << run << ": regime (Figs 9-11: bubbling, then slugging) | slugging | "
     << text(j, "bubbles", "regime")
     << fmt(" (slug in %.0f %% of frames", 100.0 * num(j, "bubbles", "slugging_fraction"))
     << fmt(", jet reaching the surface in %.0f %%)",
            100.0 * num(j, "bubbles", "spouting_fraction"))
     << " | |\n";
  md << "| " << run << ": bubbles formed, eruptions at the surface | | "
     << fmt("%.2f formed per s, ", num(j, "bubbles", "formed_per_s"))
     << fmt("%.2f eruptions per s", erupt) << " | |\n";
  md << "| " << run << ": eruptions against the dominant frequency of dp (Welch) | equal for one "
     << "bubble per cycle | " << fmt("%.2f per s against ", erupt) << fmt("%.2f Hz", f) << " | "
     << fmt("%+.0f %%", 100.0 * (erupt / f - 1.0)) << " |\n";
  md << "| " << run << ": mean rise velocity against 0.5 sqrt(g D_e) (2D, Pyle and Harrison) "
     << "| reference, not a fit | " << fmt("%.3f m/s", rise) << fmt(" at D_e %.1f mm", 1e3 * d)
     << fmt(" (reference %.3f m/s)", ref) << " | " << fmt("%+.0f %%", 100.0 * (rise / ref - 1.0))
     << " |\n";
}

// A run's dp cycle in words: the verdict of analysis/cycles.hpp with the peak it judged.
std::string cycle_words(const nlohmann::json& j) {
  std::string w = j.contains("dp_cycle") && j["dp_cycle"].is_string()
                      ? j["dp_cycle"].get<std::string>()
                      : "n/a";
  if (j.contains("dp_dominant_period_s") && j["dp_dominant_period_s"].is_number())
    w += fmt(": period %.3f s", num(j, "dp_dominant_period_s")) +
         fmt(", cycle-length spread %.0f %%", 100.0 * num(j, "dp_cycle_length_cv"));
  w += fmt("; dp %.0f Pa", num(j, "dp_mean_pa")) + fmt(" +- %.0f Pa", num(j, "dp_std_pa"));
  return w;
}

// The energy budget of a run in one sentence: what the gas put in and where it went.
std::string energy_words(const nlohmann::json& j) {
  if (!j.contains("energy")) return "no energy budget";
  const auto& e = j["energy"];
  const double gas = e.value("gas_work_j", NAN), res = e.value("residual_j", NAN);
  const double lost =
      e.value("dashpot_dissipation_j", NAN) + e.value("friction_dissipation_j", NAN);
  const double t = num(j, "sim_time_s");
  return fmt("the gas did %.3g J of work on the particles", gas) + fmt(" in %.1f s", t) +
         fmt(", the dashpots and friction took %.3g J", lost) +
         fmt(", the mechanical energy changed by %+.3g J", e.value("mechanical_change_j", NAN)) +
         fmt(", and %+.3g J is unaccounted for", res) +
         fmt(" (the integration's residual: %+.0f %% of the gas's work", 100.0 * res / gas) +
         fmt(", %+.3g W)", e.value("residual_per_s_w", NAN));
}

// The ideal case as measured, beside the paper's description and the literature.
void ideal_section(std::ostringstream& md, const nlohmann::json& ij, const nlohmann::json& gj,
                   const nlohmann::json& pj) {
  md << "## The ideal case (Figs 16-17) as measured\n\n";
  md << "The paper: \"a bubble ... generated at the jet region grows to convert to a slug, and "
     << "particles scatter over the upper part of the bed ... a bubble experiences its generation, "
     << "growth and burst-out before a new bubble is formed, and this cycle is quite stable\" "
     << "(dp swinging on a scale of 10^4 Pa).\n\n";
  auto describe = [&](const char* name, const nlohmann::json& j) {
    md << "- **" << name << "**: regime " << text(j, "bubbles", "regime")
       << fmt(" (slug in %.0f %% of the frames", 100.0 * num(j, "bubbles", "slugging_fraction"))
       << fmt(", %.2f bubbles formed per s", num(j, "bubbles", "formed_per_s"))
       << fmt(", %.2f eruptions per s)", num(j, "bubbles", "eruptions_per_s")) << "; dp "
       << cycle_words(j) << fmt(" (std / mean %.3f)", num(j, "dp_std_pa") / num(j, "dp_mean_pa"))
       << "; energy: " << energy_words(j) << ".\n";
  };
  describe("ideal case, the paper's scheme (incremental displacement)", ij);
  describe("ideal case, geometric overlap", gj);
  describe("realistic bed (eta = 0.15, gamma = 0.3)", pj);
  md << "\nMontages: ![ideal](ideal/montage.png) ![ideal, "
        "geometric](ideal_geometric/montage.png)\n\n";
  md << "Hard-sphere simulations with perfectly elastic, frictionless collisions have been "
        "reported "
     << "to fluidize homogeneously, without bubbles (Hoomans et al., Chem. Eng. Sci. 51 (1996) "
        "99): "
     << "bubbles need collisions that lose energy, so that particles cluster. An ideal bed here "
        "has "
     << "no contact losses at all; what it loses is the drag on particle fluctuations (inside the "
     << "gas's net work) and the integration's residual. Where that residual is a sizeable share "
        "of "
     << "the gas's work, the scheme itself is the bed's damping, and its behaviour follows the "
     << "numerics rather than the model; compare the two contact forms above, whose residuals "
     << "differ in sign and size (the energy study gives both for an elastic box).\n\n";
}

// One figure over the seeds (run/ensemble.hpp's entry), or the single run's value.
struct Figure {
  double mean = NAN, sd = NAN;  // sd: NaN with one seed
  std::size_t n = 0;
};

Figure figure(const std::vector<nlohmann::json>& summaries, const char* key) {
  const nlohmann::json e = ensemble_statistics(summaries);
  Figure f;
  if (!e.contains(key)) return f;
  f.mean = e[key]["mean"].get<double>();
  f.sd = e[key]["std"].is_number() ? e[key]["std"].get<double>() : NAN;
  f.n = e[key]["n"].get<std::size_t>();
  return f;
}

// "1.78 +- 0.12 m/s (3 seeds)", or the one seed's value "1.78 m/s (1 seed)".
std::string pm(const Figure& f, const char* format, const char* unit, double scale = 1.0) {
  if (f.n == 0) return "n/a";
  std::string s = fmt(format, scale * f.mean);
  if (f.n > 1) s += " +- " + fmt(format, scale * f.sd);
  return s + unit + " (" + std::to_string(f.n) + (f.n == 1 ? " seed)" : " seeds)");
}

// Whether the paper's value lies within two standard deviations of the ensemble mean.
std::string within_two_sd(const Figure& f, double paper) {
  if (f.n < 2 || !std::isfinite(f.sd)) return "one seed: spread not measured";
  return std::abs(f.mean - paper) <= 2.0 * f.sd ? "the paper's value within 2 std"
                                                : "the paper's value outside 2 std";
}

// One figure of every run (NaN where a run lacks it), as mean, standard deviation and count.
SampleStatistics over(const std::vector<nlohmann::json>& runs,
                      const std::function<double(const nlohmann::json&)>& of) {
  std::vector<double> v;
  for (const auto& j : runs)
    if (const double x = of(j); std::isfinite(x)) v.push_back(x);
  return sample_statistics(v);
}

// "2.86, 2.83 (2.85 +- 0.02)": each run's value, then the mean and spread where there are two.
std::string per_run(const std::vector<nlohmann::json>& runs, const char* f,
                    const std::function<double(const nlohmann::json&)>& of) {
  std::string s;
  for (std::size_t k = 0; k < runs.size(); ++k) s += (k ? ", " : "") + fmt(f, of(runs[k]));
  const SampleStatistics st = over(runs, of);
  if (st.n > 1) s += " (" + fmt(f, st.mean) + " +- " + fmt(f, st.std) + ")";
  return s;
}

// Whether the reference [lo, hi] (one value: lo = hi) meets mean +- 2 std of the runs.
std::string reference_within(const SampleStatistics& st, double lo, double hi) {
  if (st.n < 2 || !std::isfinite(st.std)) return "one packing: spread not measured";
  const bool meets = st.mean + 2.0 * st.std >= lo && st.mean - 2.0 * st.std <= hi;
  return meets ? "within 2 std" : "outside 2 std";
}

// The first probe's figure `key` in a run's summary.
double probe(const nlohmann::json& j, const char* key) {
  if (!j.contains("probes") || !j["probes"].is_array() || j["probes"].empty()) return NAN;
  return json_number(j["probes"][0], key);
}

}  // namespace

std::string second_bed_section(const std::vector<nlohmann::json>& runs,
                               const std::vector<std::uint64_t>& seeds) {
  std::ostringstream md;
  md << "## The second bed: van Wachem et al. (2001)\n\n";
  const std::string how =
      "`fluidbed run assets/scenes/van_wachem_2001.toml --threads 2 --bubbles` (12 s, about "
      "20 minutes a packing); docs/second-bed.md has the causes measured so far";
  if (runs.empty()) {
    md << "Not run: `--quick` leaves it out. " << how << ".\n\n";
    return md.str();
  }
  md << "`assets/scenes/van_wachem_2001.toml` as shipped (the `--set` overrides are the paper "
        "bed's and do not apply), "
     << runs.size() << (runs.size() == 1 ? " packing (lattice seed " : " packings (lattice seeds ");
  for (std::size_t k = 0; k < seeds.size(); ++k) md << (k ? ", " : "") << seeds[k];
  md << "), " << fmt("%.0f s", num(runs.front(), "sim_time_s"))
     << fmt(" with statistics from %.0f s", num(runs.front(), "averaging_start_s"))
     << ". Each figure per packing, then mean +- sample standard deviation; the experiment's "
        "figures are Lethe's reference files (its relative pressure 3 to 6 s and its bed height). "
        "The spectra's resolution is "
     << fmt("%.2f Hz", 1.0 / WelchSettings{}.segment) << " (Welch, "
     << fmt("%.0f s segments).\n\n", WelchSettings{}.segment);
  md << "| figure | experiment | fluidbed | experiment within 2 std of ours |\n|---|---|---|---|\n";
  auto row = [&](const char* what, const std::string& reference, const char* f, double lo, double hi,
                 const std::function<double(const nlohmann::json&)>& of) {
    md << "| " << what << " | " << reference << " | " << per_run(runs, f, of) << " | "
       << (std::isfinite(lo) ? reference_within(over(runs, of), lo, hi) : std::string("-"))
       << " |\n";
  };
  row("probe (0.045, 0.045) m, spectrum peak (Hz)", "2.3 to 2.4 (2.415)", "%.2f", 2.3, 2.4,
      [](const nlohmann::json& j) { return probe(j, "peak_hz"); });
  md << "| probe, cycle | regular | ";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const nlohmann::json p = runs[k].contains("probes") && runs[k]["probes"].is_array() &&
                                     !runs[k]["probes"].empty()
                                 ? runs[k]["probes"][0]
                                 : nlohmann::json::object();
    md << (k ? "; " : "") << (p.contains("cycle") ? p["cycle"].get<std::string>() : "n/a");
  }
  md << " | - |\n";
  row("probe, standard deviation (Pa)", "82", "%.1f", 82.0, 82.0,
      [](const nlohmann::json& j) { return probe(j, "std_pa"); });
  row("highest particle, lowest (m)", "0.094", "%.3f", 0.094, 0.094,
      [](const nlohmann::json& j) { return num(j, "bed_top_min_m"); });
  row("highest particle, highest (m)", "0.149", "%.3f", 0.149, 0.149,
      [](const nlohmann::json& j) { return num(j, "bed_top_max_m"); });
  md << "| regime (bubble tracker) | bubbling | ";
  for (std::size_t k = 0; k < runs.size(); ++k)
    md << (k ? ", " : "") << text(runs[k], "bubbles", "regime")
       << fmt(" (slug in %.0f %% of frames)", 100.0 * num(runs[k], "bubbles", "slugging_fraction"));
  md << " | - |\n";
  const double nan = NAN;
  row("bubbles formed per s", "-", "%.1f", nan, nan,
      [](const nlohmann::json& j) { return num(j, "bubbles", "formed_per_s"); });
  row("mean bubble D_e (mm)", "-", "%.1f", nan, nan,
      [](const nlohmann::json& j) { return 1e3 * num(j, "bubbles", "mean_d_eq_m"); });
  row("mean dp (Pa)", fmt("%.0f (W/A: the bed's weight)", num(runs.front(), "bed_weight_per_area_pa")),
      "%.1f", nan, nan,
      [](const nlohmann::json& j) { return num(j, "dp_mean_pa"); });
  md << "\nMontages: ";
  for (std::uint64_t s : seeds)
    md << "![packing " << s << "](second_bed/seeds/" << s << "/montage.png) ";
  md << "\n\nTo run one packing alone: " << how << ".\n\n";
  return md.str();
}

std::string paper_report(const ReproduceArgs& a, const PaperRuns& r, double total_wall) {
  const nlohmann::json& pj = r.paper.front();
  const nlohmann::json& ij = r.ideal;
  const nlohmann::json& gj = r.ideal_geometric;
  const std::vector<std::uint64_t>& seeds = r.seeds;
  const SweepResult& sr = r.first_sweep;
  const Figure umf = figure(r.sweeps, "umf_m_s");
  const double weight = num(pj, "bed_weight_per_area_pa");
  const double dp_mean = num(pj, "dp_mean_pa");
  const double wall_per_sim = r.paper_wall / std::max(r.paper_time, 1e-9);
  std::ostringstream md;
  md << "# fluidbed against Xu & Yu (1997)\n\n";
  md << "Made by `fluidbed reproduce" << (a.quick ? " --quick" : "")
     << (a.seeds.empty() ? "" : " --seeds " + a.seeds) << "`. Every number below "
     << "is measured by this run; none is tuned to the paper.\n\n";
  md << "A fluidized bed is chaotic: another packing of the same particles gives another run. "
     << "The paper's bed, its uniform twin and the sweep ran from " << seeds.size()
     << (seeds.size() == 1 ? " packing (lattice seed " : " packings (lattice seeds ");
  for (std::size_t k = 0; k < seeds.size(); ++k) md << (k ? ", " : "") << seeds[k];
  md << (a.quick && a.seeds.empty() ? "; `--quick` runs one, so no spread is measured" : "")
     << "). Figures marked +- are the mean and sample standard deviation over the seeds (n - 1), "
     << "with their number; the other rows, the figures and the ideal case are the first seed's "
     << "run (every seed's run is in `paper_bed/seeds/S/`, `uniform/seeds/S/` and "
     << "`sweep/seeds/S/`, their spread in each folder's `summary.json`).\n\n";
  md << "| paper figure or number | paper | fluidbed | difference |\n|---|---|---|---|\n";
  if (umf.n > 0) {
    md << "| U_mf, decreasing branch (Fig. 6, point E) | 1.8 m/s (Wen-Yu 1.77) | "
       << pm(umf, "%.2f", " m/s") << " | " << fmt("%+.0f %%", 100.0 * (umf.mean / 1.8 - 1.0))
       << "; " << within_two_sd(umf, 1.8) << " |\n";
  } else {
    md << "| U_mf, decreasing branch (Fig. 6) | 1.8 m/s | not found: " << sr.umf.why << " | |\n";
  }
  md << "| plateau of the decreasing branch / bed weight per area | about 1 | "
     << fmt("%.0f Pa / ", sr.umf.plateau) << fmt("%.0f Pa", sr.bed_weight_per_area) << " | "
     << fmt("%+.0f %%", 100.0 * (sr.umf.plateau / sr.bed_weight_per_area - 1.0)) << " |\n";
  const nlohmann::json& uj = r.uniform.front();
  const Figure dp_u = figure(r.uniform, "dp_mean_pa");
  const Figure dp_j = figure(r.paper, "dp_mean_pa");
  md << "| mean dp at 2.8 m/s, uniform distributor (model A: the bed carries its weight) | "
     << "1.005 of W/A (measured, model.md 2.1) | " << pm(dp_u, "%.0f", " Pa")
     << fmt(" (weight %.0f Pa)", weight) << " | "
     << fmt("%+.0f %%", 100.0 * (dp_u.mean / weight - 1.0)) << " |\n";
  md << "| mean dp at 2.8 m/s, central jet (eq 30, Fig. 8; dead zones rest on the floor) | "
     << "below W/A (DPMFoam 0.77) | " << pm(dp_j, "%.0f", " Pa")
     << fmt(" = %.3f of W/A", dp_j.mean / weight) << " | "
     << fmt("%.3f of the uniform bed's", dp_j.mean / dp_u.mean) << " |\n";
  md << "| dominant frequency of dp at 2.8 m/s, central jet (Welch) | | "
     << pm(figure(r.paper, "dp_spectrum.dominant_frequency_refined_hz"), "%.2f", " Hz") << " | |\n";
  md << "| mean bed height after start-up, central jet | | "
     << pm(figure(r.paper, "bed_height_mean_m"), "%.3f", " m") << " | |\n";
  md << "| start-up peak of dp (Fig. 8) | far above the stable level | "
     << fmt("%.0f Pa", num(pj, "dp_max_pa")) << fmt(" at t = %.3f s", num(pj, "dp_max_time_s"))
     << " | " << fmt("%.1f x the mean", num(pj, "dp_max_pa") / dp_mean) << " |\n";
  const Figure overlap = figure(r.paper, "max_overlap_ratio");
  md << "| max overlap ratio at start-up (Fig. 15) | 1.7 % | " << pm(overlap, "%.2f", " %", 100.0)
     << " | " << within_two_sd(overlap, 0.017) << " |\n";
  md << "| max overlap ratio after start-up (Fig. 15) | well below 1 % | "
     << fmt("%.2f %%", 100.0 * num(pj, "max_overlap_ratio_after_startup")) << " | |\n";
  md << "| ideal case: a regular dp cycle (Fig. 17) | one bubble forms, grows to a slug and "
     << "bursts before the next: quite stable | " << cycle_words(ij) << " | |\n";
  md << "| ideal case, geometric overlap: a regular dp cycle | (as above) | " << cycle_words(gj)
     << " | |\n";
  md << "| realistic bed: dp cycle | irregular | " << cycle_words(pj) << " | |\n";
  bubble_rows(md, "jetted bed", pj);
  bubble_rows(md, "uniform distributor", uj);
  bubble_rows(md, "ideal case", ij);
  bubble_rows(md, "ideal case, geometric overlap", gj);
  md << "| cost of 1 s of the paper's bed | 9 h CPU (HP-735) | " << fmt("%.0f s wall", wall_per_sim)
     << " (" << resolve_threads(r.paper_threads)
     << (resolve_threads(r.paper_threads) == 1 ? " thread)" : " threads)") << " | "
     << fmt("%.0f x faster", 9.0 * 3600.0 / wall_per_sim) << " |\n\n";
  md << "## Figures\n\n";
  // The figures of one run are the first seed's (its folder); the sweep's are the ensemble's.
  const std::string first = "seeds/" + std::to_string(seeds.front()) + "/";
  const std::string paper = "paper_bed/" + first, uniform = "uniform/" + first;
  md << "Fig. 6, the sweep (each packing's branches faint, their mean bold, U_mf's mean +- one "
     << "standard deviation): ![sweep](sweep/sweep.png)\n\n";
  md << "Fig. 8, dp against time at 2.8 m/s: ![dp](" << paper << "dp.png)\n\n";
  md << "Fig. 15, max overlap ratio: ![overlap](" << paper << "overlap.png)\n\n";
  md << "Figs 12-13, particles from the jet region: ![trajectory](" << paper
     << "trajectory.png)\n\n";
  md << "Fig. 17, the ideal case's dp: ![ideal](ideal/dp.png)\n\n";
  md << "Bubbles of the jetted bed (size against height, rise velocity against size with "
     << "0.5 sqrt(g D_e)): ![bubbles](" << paper << "bubbles.png)\n\n";
  md << "Its dp spectrum (Welch): ![spectrum](" << paper << "dp_spectrum.png); the Lacey mixing "
     << "index of the two halves by initial height: ![mixing](" << paper << "mixing.png)\n\n";
  md << "The same bed through a uniform distributor: ![uniform dp](" << uniform << "dp.png) "
     << "![uniform bubbles](" << uniform << "bubbles.png)\n\n";
  md << "The ideal case's bubbles: ![ideal bubbles](ideal/bubbles.png)\n\n";
  ideal_section(md, ij, gj, pj);
  md << second_bed_section(r.second_bed, r.second_bed_seeds);
  md << "## Studies: speed against accuracy, stability, model choices\n\n";
  md << "Each study below is `fluidbed study NAME" << (a.quick ? " --size tiny" : "")
     << "`; its table is `studies/NAME/study.csv`, its full findings `studies/NAME/summary.md`. "
     << "The advice is derived from the study's own measurements by the rule it states.\n\n";
  for (const auto& st : r.studies) {
    md << "### " << st.title << "\n\n";
    for (const auto& c : st.charts)
      md << "![" << st.name << "](studies/" << st.name << "/" << c << ")\n\n";
    md << st.advice << " (" << st.points << " points, " << st.failed << " failed runs recorded; "
       << fmt("%.0f s", st.wall_time) << "; [findings](studies/" << st.name << "/summary.md))\n\n";
  }
  md << "## Settings\n\n";
  md << "- paper bed: `assets/scenes/xu_yu_1997.toml`, " << r.paper_time << " s simulated, "
     << "averaging from " << r.averaging << " s; the same with `inlet.kind = uniform`, "
     << r.uniform_time << " s; ideal: `assets/scenes/ideal.toml`, " << r.ideal_time
     << " s, and the same with `contact.displacement = geometric`.\n";
  md << "- bubbles: the scene's `[bubbles]` settings (threshold, interval, minimum diameter); the "
     << "regime rule and the eruption count are in docs/bubbles.md.\n";
  md << "- sweep: " << sr.up.size() << " velocities, " << r.sweep_run_time
     << " s each, averaging from " << r.sweep_averaging_start
     << " s; U_mf: least-squares line through the defluidized points of "
     << "the decreasing branch meets the mean of its plateau (split at least squared error).\n";

  if (!a.overrides.empty()) {
    md << "- overrides applied to every scene:";
    for (const auto& o : a.overrides) md << " `" << o << "`";
    md << "\n";
  }
  md << "- wall time of this report: " << fmt("%.0f s", total_wall) << ".\n";
  return md.str();
}

}  // namespace fluidbed::app
