#include "run/ensemble.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/run_pool.hpp"
#include "core/text_format.hpp"
#include "scene/scene_loader.hpp"
#include "sim/placement.hpp"

namespace fluidbed {
namespace {

constexpr std::size_t kMaxSeeds = 1000;  // a guard against a typo, far above any useful ensemble

// A whole number >= 0 written in digits only; throws InputError naming the item otherwise.
std::uint64_t whole_number(const std::string& item, const std::string& text) {
  const bool digits = !item.empty() && std::all_of(item.begin(), item.end(),
                                                   [](char c) { return c >= '0' && c <= '9'; });
  errno = 0;
  const unsigned long long v = digits ? std::strtoull(item.c_str(), nullptr, 10) : 0;
  if (!digits || errno == ERANGE)
    throw InputError("--seeds " + text + ": \"" + item +
                     "\" is not a whole number (give a count N >= 1, or seeds like 3,7,11)");
  return static_cast<std::uint64_t>(v);
}

}  // namespace

void flatten_numbers(const nlohmann::json& j, const std::string& prefix,
                     std::map<std::string, double>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object())
      flatten_numbers(*it, key, out);
    else if (it->is_number() && std::isfinite(it->get<double>()))
      out[key] = it->get<double>();
  }
}

std::vector<std::uint64_t> parse_seeds(const std::string& text, std::uint64_t first) {
  std::vector<std::uint64_t> seeds;
  if (text.find(',') == std::string::npos) {
    const std::uint64_t n = whole_number(text, text);
    if (n == 0) throw InputError("--seeds 0: an ensemble needs at least one seed");
    if (n > kMaxSeeds)
      throw InputError("--seeds " + text + ": more than " + std::to_string(kMaxSeeds) + " seeds");
    for (std::uint64_t k = 0; k < n; ++k) seeds.push_back(first + k);
    return seeds;
  }
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    const std::uint64_t s = whole_number(text.substr(pos, comma - pos), text);
    if (std::find(seeds.begin(), seeds.end(), s) != seeds.end())
      throw InputError("--seeds " + text + ": seed " + std::to_string(s) +
                       " is repeated (each packing once)");
    seeds.push_back(s);
    pos = comma + 1;
  }
  if (seeds.size() > kMaxSeeds)
    throw InputError("--seeds " + text + ": more than " + std::to_string(kMaxSeeds) + " seeds");
  return seeds;
}

std::uint64_t lattice_seed(const Settings& scene) {
  if (scene.packing_seed) return *scene.packing_seed;
  if (scene.particles.placement == Placement::Packed && !scene.particles.packing_scene.empty())
    return load_scene(scene_path(scene, scene.particles.packing_scene)).particles.seed;
  return scene.particles.seed;
}

void check_seeded_start(const Settings& scene) {
  if (scene.particles.placement != Placement::Lattice &&
      scene.particles.placement != Placement::Packed)
    throw InputError("--seeds: the scene's particles start from particles.placement = \"" +
                     std::string(option_string(scene.particles.placement)) +
                     "\", which no seed changes (an ensemble needs \"lattice\" or \"packed\")");
}

Settings with_seed(Settings scene, std::uint64_t seed) {
  scene.particles.seed = seed;
  scene.packing_seed = seed;
  return scene;
}

SampleStatistics sample_statistics(const std::vector<double>& v) {
  SampleStatistics s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  if (s.n > 1) {
    double sq = 0.0;
    for (double x : v) sq += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(sq / (s.n - 1));
  }
  return s;
}

nlohmann::json ensemble_statistics(const std::vector<nlohmann::json>& summaries) {
  std::map<std::string, std::vector<double>> values;
  for (const auto& s : summaries) {
    std::map<std::string, double> flat;
    flatten_numbers(s, "", flat);
    for (const auto& [k, v] : flat) values[k].push_back(v);
  }
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [k, v] : values) {
    const SampleStatistics s = sample_statistics(v);
    out[k] = {{"mean", s.mean},
              {"std", s.n > 1 ? nlohmann::json(s.std) : nlohmann::json(nullptr)},
              {"min", s.min},
              {"max", s.max},
              {"n", v.size()}};
  }
  return out;
}

nlohmann::json ensemble_summary(const std::vector<nlohmann::json>& summaries,
                                const std::vector<std::uint64_t>& seeds) {
  nlohmann::json j = nlohmann::json::object();
  const nlohmann::json stats = ensemble_statistics(summaries);
  if (!summaries.empty())
    for (auto it = summaries.front().begin(); it != summaries.front().end(); ++it) {
      if (it->is_number() && !it->is_boolean() && stats.contains(it.key())) {
        j[it.key()] = stats[it.key()]["mean"];
      } else if (it->is_string() || it->is_boolean()) {
        const bool same = std::all_of(summaries.begin(), summaries.end(), [&](const auto& s) {
          return s.contains(it.key()) && s[it.key()] == *it;
        });
        if (same) j[it.key()] = *it;
      }
    }
  nlohmann::json hashes = nlohmann::json::object();
  for (std::size_t k = 0; k < summaries.size() && k < seeds.size(); ++k)
    if (summaries[k].contains("state_hash"))
      hashes[std::to_string(seeds[k])] = summaries[k]["state_hash"];
  j.erase("state_hash");
  if (!hashes.empty()) j["state_hashes"] = hashes;
  j["seeds"] = seeds;
  j["seeds_folder"] = "seeds/S (one folder per seed, each run's usual files)";
  j["std_kind"] = "sample standard deviation over the seeds (divided by n - 1); null when n = 1";
  j["ensemble"] = stats;
  return j;
}

std::string ensemble_line(const nlohmann::json& e, const char* f) {
  auto num = [&](double v) { return format_number(f, v); };
  std::string s = num(e.at("mean").get<double>());
  s += e.at("std").is_number() ? " +- " + num(e.at("std").get<double>()) : " (no spread: one seed)";
  s += " (" + num(e.at("min").get<double>()) + " to " + num(e.at("max").get<double>()) +
       ", n = " + std::to_string(e.at("n").get<std::size_t>()) + ")";
  return s;
}

std::string member_dir(const std::string& dir, std::uint64_t seed) {
  return (std::filesystem::path(dir) / "seeds" / std::to_string(seed)).string();
}

EnsembleResult run_ensemble(const EnsembleJob& job, bool resume) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(job.dir, ec);
  if (ec) throw InputError("cannot create output folder " + job.dir + ": " + ec.message());
  const fs::path dir(job.dir);
  fs::remove(dir / "summary.json", ec);  // only a finished ensemble has one
  if (!resume || !fs::exists(dir / "ensemble.json")) {  // a resumed one not begun has none yet
    nlohmann::json identity = {{"format", 1}};
    for (const auto& [key, value] : job.identity.items()) identity[key] = value;
    identity["seeds"] = job.seeds;
    write_file_atomically((dir / "ensemble.json").string(),
                          [&](std::ostream& o) { o << identity.dump(2) << "\n"; });
  }
  EnsembleResult r;
  r.summaries.assign(job.seeds.size(), nullptr);
  std::vector<int> done(job.seeds.size(), 0);
  std::vector<std::function<void()>> tasks;
  for (std::size_t k = 0; k < job.seeds.size(); ++k)
    tasks.push_back([&, k] {
      if (std::optional<nlohmann::json> s =
              job.member(k, job.seeds[k], member_dir(job.dir, job.seeds[k]))) {
        r.summaries[k] = std::move(*s);
        done[k] = 1;
      }
    });
  RunPool(std::max(1, job.side_by_side)).run(tasks);
  r.complete = std::find(done.begin(), done.end(), 0) == done.end();
  if (r.complete && job.summary) {
    r.summary = ensemble_summary(r.summaries, job.seeds);
    write_file_atomically((dir / "summary.json").string(),
                          [&](std::ostream& o) { o << r.summary.dump(2) << "\n"; });
  }
  return r;
}

nlohmann::json read_ensemble_identity(const std::string& dir, const std::string& kind,
                                      const std::string& head) {
  const std::string path = (std::filesystem::path(dir) / "ensemble.json").string();
  std::ifstream in(path);
  if (!in) throw InputError(head + "it holds no ensemble (no " + path + ")");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("format", 0) != 1 ||
      j.value("kind", std::string()) != kind)
    throw InputError(head + path + " is not the record of a " + kind + " ensemble");
  return j;
}

bool holds_ensemble(const std::string& dir) {
  return std::filesystem::is_regular_file(std::filesystem::path(dir) / "ensemble.json");
}

}  // namespace fluidbed
