#pragma once
// The instruction sets the vectorised loops are built for. A function marked
// FLUIDBED_SIMD_CLONES is compiled three times, for AVX-512, AVX2 and plain x86-64, and the
// loader takes the best build the CPU runs (GCC's target_clones). The builds give the same bits:
// no fused multiply-add in any of them (-ffp-contract=off, CMakeLists.txt), and loops written
// with the scalar law's operations in the scalar law's order.
#define FLUIDBED_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
