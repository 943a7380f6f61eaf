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
// The touching slots and what the law needs besides the particles (the monolayer's or a thick
// slab's arrays): the slots' pairs and history (a thick slab's shear vector is ds, ds_y, ds_z), the
// law, the displacement form and the step.
template <class KernelParticles>
struct ContactIn {
  KernelParticles p;
  const std::int32_t *li, *lj;
  const double *dn, *ds;
  const std::int32_t* on;
  std::int64_t count;
  ContactParams params;  // a thick slab: mu_r > 0 adds rolling resistance
  bool incremental;
  double dtau;  // s
  const double *ds_y = nullptr, *ds_z = nullptr;
};
using PairContactIn = ContactIn<PairKernelParticles>;
struct PairContactOut {
  double *dn, *ds, *fx, *fy, *ft, *ratio, *dashpot, *friction;
  std::int32_t* sliding;
};
void pair_contacts(const PairContactIn& in, const PairContactOut& out);

// The same two kernels as one build each (core/simd.hpp: AVX-512, AVX2 or plain x86-64), for
// the tests that pin every build to the scalar law, not only the one this CPU takes. The CPU must
// run the build (cpu_runs).
void classify_pairs_on(SimdBuild b, const PairKernelParticles& p, const std::int32_t* li,
                       const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                       std::uint8_t* code);
void pair_contacts_on(SimdBuild b, const PairContactIn& in, const PairContactOut& out);

// A thick slab's kernels (dem/depth_kernel.cpp, used by dem/depth_passes.cpp): the same two
// steps in three dimensions, the law of contact_force_3d with the rolling resistance of
// rolling_torque_3d, the operations in their order. The particles' arrays they read:
struct DepthKernelParticles {
  const double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz, *r, *inv_inertia;
  const double* mass = nullptr;  // read by the Hertz-Mindlin law only
};

// Candidate slots [k0, k1): code[k - k0] as classify_pairs, with the distance in 3D.
void classify_pairs_depth(const DepthKernelParticles& p, const std::int32_t* li,
                          const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                          std::uint8_t* code);

// The touching slots on[0 .. count) (k, or ~k for a fresh contact, whose history the caller
// clears), as for pair_contacts, with the shear vector's ds_y and ds_z.
using DepthContactIn = ContactIn<DepthKernelParticles>;
// Per contact q: the new history, the force on li[k], the lever n x F_t (the torque on a sphere
// is its radius times it), the rolling torque on li[k] (zero without rolling resistance), the
// overlap ratio, the energy lost over the step (friction includes the rolling resistance's) and
// whether it slides.
struct DepthContactOut {
  double *dn, *ds, *ds_y, *ds_z;
  double *fx, *fy, *fz, *lever_x, *lever_y, *lever_z, *roll_x, *roll_y, *roll_z;
  double *ratio, *dashpot, *friction;
  std::int32_t* sliding;
};
void depth_contacts(const DepthContactIn& in, const DepthContactOut& out);

// The contacts of a thick slab's spheres with its walls (the bottom, sides and lid and the front
// and back walls; dem/walls.hpp), listed in on[0 .. count) by the walls' history entry
// s = i * walls + c of sphere i = particle[q] and wall c (~s for a contact that touches for the
// first time, whose history the caller clears): the law of the pairs with R* = R_i, m* = m_i
// and the wall at rest, the rolling resistance against the sphere's spin. Writes per contact what
// depth_contacts writes, with the ratio overlap / R_i.
struct WallContactIn {
  DepthKernelParticles p;
  const std::int32_t *on, *particle;
  std::int64_t count;
  std::int32_t walls;
  const double *nx, *ny, *nz, *offset;  // per wall: its inward unit normal and offset (m)
  const double *dn, *ds, *ds_y, *ds_z;  // the walls' history, by entry s
  ContactParams params;                 // the walls' law
  bool incremental;
  double dtau;  // s
};
void wall_contacts_depth(const WallContactIn& in, const DepthContactOut& out);

// Each build of the three (for the tests, as classify_pairs_on).
void wall_contacts_depth_on(SimdBuild b, const WallContactIn& in, const DepthContactOut& out);
void classify_pairs_depth_on(SimdBuild b, const DepthKernelParticles& p, const std::int32_t* li,
                             const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                             std::uint8_t* code);
void depth_contacts_on(SimdBuild b, const DepthContactIn& in, const DepthContactOut& out);

// After classify: the touching slots of [k0, k1) listed in on (k, or ~k for one that touches for
// the first time, whose history clear(k) zeroes), the slots' touching flags updated, and a
// coincident pair's overlap of 1 taken into max_ratio (the first such slot into worst). Returns
// the count.
template <class Clear>
std::int64_t list_touching(const std::uint8_t* code, std::uint8_t* touch, std::int64_t k0,
                           std::int64_t k1, std::int32_t* on, double& max_ratio,
                           std::int64_t& worst, Clear clear) {
  std::int64_t count = 0;
  for (std::int64_t k = k0; k < k1; ++k) {
    const int c = code[k - k0];
    const int touching = c & 1, fresh = touching & (touch[k] ^ 1);
    on[count] = static_cast<std::int32_t>(k) ^ -fresh;
    count += touching;
    touch[k] = static_cast<std::uint8_t>(touching);
    if (fresh) clear(k);  // rare: the branch is well predicted
    if ((c >> 1) && 1.0 > max_ratio) {
      max_ratio = 1.0;
      worst = k;
    }
  }
  return count;
}

// The slot of a listed contact (on[q] is k, or ~k for a fresh one).
inline std::int32_t listed_slot(std::int32_t s) {
  return s ^ (s >> 31);
}

}  // namespace fluidbed
