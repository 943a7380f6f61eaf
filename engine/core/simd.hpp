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

// Calls the build b of a kernel, given its three entry points (AVX-512, AVX2, plain x86-64).
template <class Avx512f, class Avx2, class Baseline, class... Args>
void call_build(SimdBuild b, Avx512f avx512f, Avx2 avx2, Baseline baseline, const Args&... args) {
  switch (b) {
    case SimdBuild::avx512f:
      return avx512f(args...);
    case SimdBuild::avx2:
      return avx2(args...);
    case SimdBuild::baseline:
      return baseline(args...);
  }
}

// A contact kernel's loops Either(in, out) built for one instruction set each, and the build b
// of them called. Either must be inlined into each (always_inline) for the build to be its own.
template <auto Either, class In, class Out>
FLUIDBED_SIMD_AVX512F void build_avx512f(const In& in, const Out& out) {
  Either(in, out);
}
template <auto Either, class In, class Out>
FLUIDBED_SIMD_AVX2 void build_avx2(const In& in, const Out& out) {
  Either(in, out);
}
template <auto Either, class In, class Out>
void build_baseline(const In& in, const Out& out) {
  Either(in, out);
}
template <auto Either, class In, class Out>
void call_contacts_build(SimdBuild b, const In& in, const Out& out) {
  call_build(b, build_avx512f<Either, In, Out>, build_avx2<Either, In, Out>,
             build_baseline<Either, In, Out>, in, out);
}

}  // namespace fluidbed
