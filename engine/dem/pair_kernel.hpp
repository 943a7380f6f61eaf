#pragma once
// The arithmetic of the pair pass over flat arrays, branch-free so that the compiler handles
// several pairs at a time (built for AVX-512 and AVX2 as well, chosen at run time: core/simd.hpp):
// which pairs touch, and the contact law (dem/contact_law.hpp, eqs 3-7 and 13-17) for those that
// do. The operations and their order are those of the scalar law, so the results are the same bits
// on every instruction set.
#include <cstdint>

#include "core/simd.hpp"
#include "dem/contact_law.hpp"

namespace fluidbed {

// The particles' arrays the kernels read.
struct PairKernelParticles {
  const double *x, *y, *vx, *vy, *w, *r;
};

// Candidate slots [k0, k1) with particles li[k] < lj[k]: code[k - k0] = 1 when they touch, 2 when
// their centres coincide (caught as an overlap of 1), 0 apart.
void classify_pairs(const PairKernelParticles& p, const std::int32_t* li, const std::int32_t* lj,
                    std::int64_t k0, std::int64_t k1, std::uint8_t* code);

// The contacts of the touching slots on[0 .. count): on[q] is the slot k, or ~k for a pair that
// touches for the first time (with the incremental displacement its first increment covers only
// the time since it touched, eq 13). Reads the slot's history from dn, ds (zero for a fresh
// contact: the caller clears it); writes per contact (index q): the new history, the force on li[k]
// (x, y and the tangential component), the overlap ratio, the energy lost over the step of dtau
// and whether it slides.
struct PairContactOut {
  double *dn, *ds, *fx, *fy, *ft, *ratio, *dashpot, *friction;
  std::int32_t* sliding;
};
void pair_contacts(const PairKernelParticles& p, const std::int32_t* li, const std::int32_t* lj,
                   const double* dn, const double* ds, const std::int32_t* on, std::int64_t count,
                   const ContactParams& params, bool incremental, double dtau,
                   const PairContactOut& out);

// The same two kernels as one build each (core/simd.hpp: AVX-512, AVX2 or plain x86-64), for
// the tests that pin every build to the scalar law, not only the one this CPU takes. The CPU must
// run the build (cpu_runs).
void classify_pairs_on(SimdBuild b, const PairKernelParticles& p, const std::int32_t* li,
                       const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                       std::uint8_t* code);
void pair_contacts_on(SimdBuild b, const PairKernelParticles& p, const std::int32_t* li,
                      const std::int32_t* lj, const double* dn, const double* ds,
                      const std::int32_t* on, std::int64_t count, const ContactParams& params,
                      bool incremental, double dtau, const PairContactOut& out);

}  // namespace fluidbed
