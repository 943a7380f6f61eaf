#pragma once
// The one counter of the benchmark binary: seconds per unit of work (a particle, a cell, a cell
// and SIMPLE iteration), with what the unit is in the label. Google Benchmark's CSV reporter
// takes its columns from the first benchmark it reports and stops on a counter it has not seen,
// so every benchmark that counts uses this name and says the rest in its label
// (bench/results-<cpu>.csv is written that way).
#include <benchmark/benchmark.h>

#include <string>

namespace fluidbed {

// `units` of work per iteration of the benchmark's loop.
inline void time_per_unit(benchmark::State& state, double units, const std::string& label) {
  state.counters["s_per_unit"] = benchmark::Counter(
      units, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetLabel(label);
}

}  // namespace fluidbed
