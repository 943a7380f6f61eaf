#pragma once
// Ensembles over packings (`--seeds`): the same scene started from N packings, each from its own
// lattice seed (`[particles] seed`), and the spread of every figure of the runs' summaries.
// A fluidized bed is chaotic, so one run's U_mf or mean dp is one sample; the ensemble says how
// far another packing moves it.
//
// The seeds: `--seeds N` (a whole number N >= 1) is the scene's own lattice seed s0 and
// s0 + 1, ..., s0 + N - 1, so the first member is the run without --seeds, bit for bit;
// `--seeds A,B,...` (two or more distinct whole numbers) is those seeds.
//
// The statistics: every numeric value of the members' summary.json (booleans, strings and arrays
// left out), nested objects flattened with '.' ("dp_spectrum.dominant_frequency_hz",
// "bubbles.formed_per_s"), as {mean, std, min, max, n}: n the members where the value is a
// number (a null, e.g. no bubble tracked, is not counted), std the sample standard deviation
// (divided by n - 1), null when n = 1.
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed {

// Every finite number of `j` into `out`, nested objects flattened with '.' below `prefix` ("" at
// the top): the values the ensemble's statistics are taken of.
void flatten_numbers(const nlohmann::json& j, const std::string& prefix,
                     std::map<std::string, double>& out);

// `--seeds TEXT` as the list of seeds (see above), `first` being the scene's seed s0. Throws
// InputError (one line naming the problem) for 0, a repeated seed, a number that is not whole
// or not a number.
std::vector<std::uint64_t> parse_seeds(const std::string& text, std::uint64_t first);

// The lattice seed the scene's particles start from: particles.seed, or for a packed bed made by
// particles.packing_scene, that scene's seed (or the packing_seed already set).
std::uint64_t lattice_seed(const Settings& scene);

// Throws InputError when the seed does not decide the scene's start (a single particle, a state
// file): an ensemble over packings needs a lattice or packed start.
void check_seeded_start(const Settings& scene);

// The scene started from the packing of `seed`: particles.seed and packing_seed set.
Settings with_seed(Settings scene, std::uint64_t seed);

// The spread of one figure over the members: mean, sample standard deviation (n - 1; NaN when
// n < 2), min, max and n (NaN for the others when n = 0).
struct SampleStatistics {
  double mean = NAN, std = NAN, min = NAN, max = NAN;
  int n = 0;
};
SampleStatistics sample_statistics(const std::vector<double>& values);

// {key: {mean, std, min, max, n}} over the members' summaries (see above).
nlohmann::json ensemble_statistics(const std::vector<nlohmann::json>& summaries);

// The ensemble's summary.json: `seeds`, `ensemble` (ensemble_statistics), `std_kind`; the
// members' top-level numbers as their ensemble means and their strings where every member has the
// same one (scene, kind, ...); `state_hashes` {seed: hash} when the members have one.
nlohmann::json ensemble_summary(const std::vector<nlohmann::json>& summaries,
                                const std::vector<std::uint64_t>& seeds);

// "mean +- std (min to max, n = N)" of one ensemble entry, numbers with printf's format `f`.
std::string ensemble_line(const nlohmann::json& entry, const char* f = "%.4g");

// ---- The one ensemble driver: `run --seeds`, `sweep --seeds`, `study NAME --seeds` and the
// ensembles of `reproduce` ----------------------------------------------------------------------
//
// One folder layout for all of them:
//   DIR/ensemble.json   what the ensemble is (written when it starts; a resume reads it back):
//                       {"format": 1, "kind": ..., "seeds": [...], and the kind's own fields}
//   DIR/seeds/S/        each member, the packing of lattice seed S (a run, a sweep, a study)
//   DIR/summary.json    once every member finished: the members' statistics (ensemble_summary)
//                       when the kind has summaries

struct EnsembleJob {
  std::string dir;
  std::vector<std::uint64_t> seeds;
  // DIR/ensemble.json's fields besides format and seeds (at least "kind").
  nlohmann::json identity = nlohmann::json::object();
  int side_by_side = 1;  // members at once (each on its own thread)
  // DIR/summary.json over the members' summaries (false: the caller writes its own result).
  bool summary = true;
  // Runs (or reads back) one member in its folder; its summary, or nothing when it was stopped.
  // It may throw: the first exception is rethrown once the other members ended.
  std::function<std::optional<nlohmann::json>(std::size_t k, std::uint64_t seed,
                                              const std::string& dir)>
      member;
};

struct EnsembleResult {
  bool complete = false;  // every member finished (else a stop ended some: resume the ensemble)
  std::vector<nlohmann::json> summaries;  // in seed order (null for a member not finished)
  nlohmann::json summary;                 // DIR/summary.json when written
};

// DIR/seeds/S.
std::string member_dir(const std::string& dir, std::uint64_t seed);
// Runs the ensemble: a new one (resume false) writes DIR/ensemble.json first; either way an
// earlier DIR/summary.json goes (only a finished ensemble has one) and is written at the end.
EnsembleResult run_ensemble(const EnsembleJob& job, bool resume);
// DIR/ensemble.json of kind `kind`; InputError of one line (starting with `head`) when there is
// none, it is unreadable or of another kind.
nlohmann::json read_ensemble_identity(const std::string& dir, const std::string& kind,
                                      const std::string& head);
// Whether DIR holds an ensemble (an ensemble.json) of any kind.
bool holds_ensemble(const std::string& dir);

}  // namespace fluidbed
