// `study NAME --seeds`: the members' study.csv side by side (study.hpp, write_study_ensemble).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "run/ensemble.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study {
namespace {
namespace fs = std::filesystem;

// The rows of a CSV file as written by Table::csv (quotes around a value with a comma or a quote,
// "" inside them for a quote).
std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path.string());
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> row(1);
    bool quoted = false;
    for (std::size_t k = 0; k < line.size(); ++k) {
      const char c = line[k];
      if (quoted && c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
        row.back() += '"';
        ++k;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        row.emplace_back();
      } else {
        row.back() += c;
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

bool parse_number(const std::string& text, double& v) {
  if (text.empty()) return false;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(v);
}

using Stat = SampleStatistics;  // run/ensemble.hpp

// Student's t at 95 % (two-sided) for `df` degrees of freedom.
double t95(int df) {
  static const double t[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                             2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                             2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  return df < 1 ? NAN : df <= 30 ? t[df - 1] : 1.96;
}


// The study's bounds (Info::bounds) judged on each point's mean over the seeds, not settled where
// a bound lies within two standard errors of that mean; and the cheapest point within every
// bound and settled, by its first cost column.
std::string bounds_over_seeds(const std::vector<Bound>& bounds,
                              const std::vector<std::string>& columns,
                              const std::vector<std::vector<std::string>>& first,
                              const std::vector<std::vector<Stat>>& stats, std::size_t seeds) {
  auto column = [&](const std::string& name) {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? std::size_t{0} : static_cast<std::size_t>(it - columns.begin());
  };
  std::size_t cost = 0;
  for (std::size_t c = 1; c < columns.size() && !cost; ++c)
    if (columns[c].rfind("cost", 0) == 0) cost = c;
  std::ostringstream md;
  md << "## Bounds over the packings\n\nEach point's bounds judged on its mean over the seeds "
        "(mean +- two standard errors, the standard deviation over sqrt(n)): a bound is not "
        "settled where it lies within two standard errors of the mean, so that the ensemble "
        "cannot tell on which side the point falls (more seeds would).\n\n| point |";
  for (const Bound& b : bounds) md << " `" << b.column << "` |";
  md << (cost ? " `" + columns[cost] + "` |" : std::string()) << " verdict |\n|---|";
  for (std::size_t k = 0; k <= bounds.size() + (cost ? 1 : 0); ++k) md << "---|";
  md << "\n";
  std::size_t best = 0;
  for (std::size_t r = 0; r < stats.size(); ++r) {
    const auto two_se = [&](const char* name) {
      const Stat& s = stats[r][column(name)];
      return s.n > 1 ? 2.0 * s.std / std::sqrt(s.n) : NAN;
    };
    const Verdict v = judge(
        bounds, [&](const char* name) { return stats[r][column(name)].mean; }, two_se);
    md << "| " << first[r + 1][0] << " |";
    for (const Bound& b : bounds) {
      const Stat& s = stats[r][column(b.column)];
      const double e = two_se(b.column);
      md << " " << (s.n ? fmt("%.3g", s.mean) : "-") << (std::isfinite(e) ? " +- " + fmt("%.2g", e) : "");
      if (s.n && static_cast<std::size_t>(s.n) < seeds)
        md << " (" << s.n << " of " << seeds << " seeds)";
      md << " |";
    }
    if (cost) md << " " << table_number(stats[r][cost].mean) << " |";
    md << " " << v.text << " |\n";
    if (r > 0 && cost && v.within && v.settled &&
        (!best || stats[r][cost].mean < stats[best][cost].mean))
      best = r;
  }
  if (cost)
    md << "\n"
       << (best ? "Cheapest within every bound, settled by the ensemble: `" + first[best + 1][0] +
                      "` (" + table_number(stats[best][cost].mean) + " `" + columns[cost] + "`)."
                : std::string("No point after the first is within every bound and settled by "
                              "the ensemble."))
       << "\n";
  md << "\n";
  return md.str();
}

}  // namespace

void write_study_ensemble(const Info& info, const std::string& dir,
                          const std::vector<std::uint64_t>& seeds, Size size) {
  std::vector<std::vector<std::vector<std::string>>> tables;
  for (std::uint64_t seed : seeds)
    tables.push_back(read_csv(fs::path(dir) / "seeds" / std::to_string(seed) / "study.csv"));
  const auto& first = tables.front();
  if (first.size() < 2) throw InputError(dir + ": the members' study.csv hold no points");
  for (std::size_t m = 1; m < tables.size(); ++m) {
    bool same = tables[m].size() == first.size() && tables[m][0] == first[0];
    for (std::size_t r = 1; same && r < first.size(); ++r)
      same = tables[m][r].size() == first[r].size() && tables[m][r][0] == first[r][0];
    if (!same)
      throw InputError(dir + ": the members' study.csv differ in their columns or points (seed " +
                       std::to_string(seeds[m]) + ")");
  }
  const std::vector<std::string>& columns = first[0];
  // stats[r][c]: row r (0: the first point) and column c over the seeds, and values[r][c] each
  // member's number (NaN where it has none); n = 0 for a column that is not a number in every
  // member where it is set (labels, failure kinds).
  std::vector<std::vector<Stat>> stats(first.size() - 1, std::vector<Stat>(columns.size()));
  std::vector<std::vector<std::vector<double>>> values(
      first.size() - 1, std::vector<std::vector<double>>(columns.size()));
  std::ostringstream csv;
  csv << "point,label,column,mean,std,min,max,n\n";
  for (std::size_t r = 1; r < first.size(); ++r)
    for (std::size_t c = 1; c < columns.size(); ++c) {
      std::vector<double> v, each;
      bool numeric = true;
      for (const auto& t : tables) {
        double x = 0.0;
        const std::string& text = t[r][c];
        if (parse_number(text, x))
          v.push_back(x);
        else if (!text.empty())
          numeric = false;
        each.push_back(parse_number(text, x) ? x : NAN);
      }
      if (!numeric || v.empty()) continue;
      values[r - 1][c] = each;
      const Stat s = sample_statistics(v);
      stats[r - 1][c] = s;
      csv << r << ',' << csv_text(first[r][0]) << ',' << csv_text(columns[c]) << ',' << table_number(s.mean)
          << ',' << table_number(s.std) << ',' << table_number(s.min) << ',' << table_number(s.max) << ',' << s.n << '\n';
    }
  write_text((fs::path(dir) / "ensemble.csv").string(), csv.str());

  std::string seed_list, seed_option;
  for (std::uint64_t s : seeds) {
    if (!seed_option.empty()) {
      seed_list += ", ";
      seed_option += ',';
    }
    seed_list += std::to_string(s);
    seed_option += std::to_string(s);
  }
  std::ostringstream md;
  md << "# Study `" << info.name << "` over " << seeds.size() << " packings: " << info.title
     << "\n\n"
     << "Made by `fluidbed study " << info.name << (size == Size::Tiny ? " --size tiny" : "")
     << " --seeds " << seed_option
     << "`: the whole study once per packing of the bed (lattice seeds " << seed_list
     << "), each in `seeds/S/` with its own study.csv, charts and summary.md. `ensemble.csv` "
        "gives every number of study.csv as its mean, standard deviation (n - 1), min and max "
        "over the seeds.\n\n"
     << "## Differences one run cannot tell\n\n"
        "Each point against the first (`"
     << first[1][0]
     << "`): where their difference of means is smaller than one run's spread (the larger of "
        "the two standard deviations over the seeds), a comparison of single runs says nothing, "
        "and only the ensemble can: both points of a seed start from the same packing, so it "
        "takes the difference seed by seed and resolves it when their mean lies further from zero "
        "than Student's t at 95 % (n - 1 degrees of freedom: 12.7 for two seeds, 4.3 for three, "
        "2.8 for five) times its standard error (their standard deviation over sqrt(n)). Costs are measured, "
        "not simulated, and are left out, and so are points whose values are the same in every "
        "seed.\n\n";
  int unresolved = 0, resolved = 0, compared = 0;
  for (std::size_t c = 1; c < columns.size(); ++c) {
    if (columns[c].rfind("cost", 0) == 0 || columns[c].find("wall") != std::string::npos ||
        columns[c].find("per_s") != std::string::npos)
      continue;
    const Stat& base = stats[0][c];
    for (std::size_t r = 1; r < stats.size(); ++r) {
      const Stat& s = stats[r][c];
      if (base.n < 2 || s.n < 2) continue;
      if (s.std == 0.0 && base.std == 0.0) continue;  // a setting, the same in every seed
      std::vector<double> d;  // seed by seed
      for (std::size_t m = 0; m < seeds.size(); ++m)
        if (std::isfinite(values[r][c][m]) && std::isfinite(values[0][c][m]))
          d.push_back(values[r][c][m] - values[0][c][m]);
      const Stat paired = sample_statistics(d);
      if (paired.n < 2 || (paired.min == 0.0 && paired.max == 0.0)) continue;
      ++compared;
      const double diff = paired.mean, spread = std::max(s.std, base.std);
      if (!(std::fabs(diff) < spread)) continue;
      const bool sure =
          std::fabs(diff) > t95(paired.n - 1) * paired.std / std::sqrt(paired.n);
      ++(sure ? resolved : unresolved);
      md << "- `" << columns[c] << "`, `" << first[r + 1][0] << "`: " << table_number(s.mean) << " +- "
         << table_number(s.std) << " against " << table_number(base.mean) << " +- " << table_number(base.std) << " (difference "
         << table_number(diff) << " +- " << table_number(paired.std) << " seed by seed, one run's spread " << table_number(spread)
         << "): "
         << (sure ? "the ensemble resolves it"
                  : "the ensemble does not resolve it either")
         << ".\n";
    }
  }
  md << "\n" << compared << " differences compared; " << resolved + unresolved
     << " of them are smaller than one run's spread (" << resolved
     << " resolved by the ensemble, " << unresolved << " not). The rest are larger than a run's "
     << "spread: a single run's comparison stands for those.\n\n";
  if (!info.bounds.empty()) md << bounds_over_seeds(info.bounds, columns, first, stats, seeds.size());
  md << "## The members\n\n";
  for (std::uint64_t s : seeds)
    md << "- seed " << s << ": [seeds/" << s << "/summary.md](seeds/" << s << "/summary.md)\n";
  write_text((fs::path(dir) / "summary.md").string(), md.str());
}

}  // namespace fluidbed::app::study
