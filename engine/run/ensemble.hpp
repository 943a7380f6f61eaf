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
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed {

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

// {key: {mean, std, min, max, n}} over the members' summaries (see above).
nlohmann::json ensemble_statistics(const std::vector<nlohmann::json>& summaries);

// The ensemble's summary.json: `seeds`, `ensemble` (ensemble_statistics), `std_kind`; the
// members' top-level numbers as their ensemble means and their strings where every member has the
// same one (scene, kind, ...); `state_hashes` {seed: hash} when the members have one.
nlohmann::json ensemble_summary(const std::vector<nlohmann::json>& summaries,
                                const std::vector<std::uint64_t>& seeds);

// "mean +- std (min to max, n = N)" of one ensemble entry, numbers with printf's format `f`.
std::string ensemble_line(const nlohmann::json& entry, const char* f = "%.4g");

}  // namespace fluidbed
