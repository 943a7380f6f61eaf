#pragma once
// The instruction sets the vectorised loops are built for. A function marked
// FLUIDBED_SIMD_CLONES is compiled three times, for AVX-512, AVX2 and plain x86-64, and the
// loader takes the best build the CPU runs (GCC's target_clones). The builds give the same bits:
// no fused multiply-add in any of them (-ffp-contract=off, CMakeLists.txt), and loops written
// with the scalar law's operations in the scalar law's order.
//
// Tests pin every build to the scalar law, not only the one this CPU takes: a kernel that offers
// its loop built for one set at a time (dem/pair_kernel.hpp: classify_pairs_on,
// pair_contacts_on) compiles the same loop in the same file with FLUIDBED_SIMD_AVX512F or
// FLUIDBED_SIMD_AVX2 (or neither: plain x86-64), and the test runs each build the CPU runs.
#include <array>
#include <cstddef>

#define FLUIDBED_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#define FLUIDBED_SIMD_AVX512F __attribute__((target("avx512f")))
#define FLUIDBED_SIMD_AVX2 __attribute__((target("avx2")))

namespace fluidbed {

// One build of a FLUIDBED_SIMD_CLONES loop.
enum class SimdBuild { avx512f, avx2, baseline };
inline constexpr std::array<SimdBuild, 3> kSimdBuilds = {SimdBuild::avx512f, SimdBuild::avx2,
                                                         SimdBuild::baseline};

inline const char* to_string(SimdBuild b) {
  static constexpr const char* kNames[] = {"avx512f", "avx2", "baseline"};  // the enum's order
  return kNames[static_cast<std::size_t>(b)];
}

// Whether this CPU runs the build (the baseline: always).
inline bool cpu_runs(SimdBuild b) {
  __builtin_cpu_init();
  switch (b) {
    case SimdBuild::avx512f:
      return __builtin_cpu_supports("avx512f");
    case SimdBuild::avx2:
      return __builtin_cpu_supports("avx2");
    case SimdBuild::baseline:
      return true;
  }
  return false;
}

}  // namespace fluidbed
