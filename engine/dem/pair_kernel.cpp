#include "dem/pair_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "core/simd.hpp"

namespace fluidbed {

namespace {

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
// of them called.
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

// The loops, inlined into each entry point below: the clones the loader chooses between
// (FLUIDBED_SIMD_CLONES) and the builds for one instruction set each (classify_pairs_on,
// pair_contacts_on), so that all are the same source compiled in this file with its flags.
__attribute__((always_inline)) inline void classify_loop(const PairKernelParticles& p,
                                                         const std::int32_t* li,
                                                         const std::int32_t* lj, std::int64_t k0,
                                                         std::int64_t k1, std::uint8_t* code) {
  const double *x = p.x, *y = p.y, *r = p.r;
#pragma omp simd
  for (std::int64_t k = k0; k < k1; ++k) {
    const std::int32_t i = li[k], j = lj[k];
    const double px = x[j] - x[i], py = y[j] - y[i];
    const double R = r[i] + r[j];
    const double L2 = px * px + py * py;
    const int coincident = L2 <= 0.0;
    const int touching = (L2 < R * R) & (coincident ^ 1);
    code[k - k0] = static_cast<std::uint8_t>(touching | (coincident << 1));
  }
}

// One loop per displacement form (a choice inside the loop would keep the compiler from
// vectorising it).
template <bool Incremental>
__attribute__((always_inline)) inline void contacts_loop(const PairContactIn& in,
                                                         const PairContactOut& out) {
  const PairKernelParticles& p = in.p;
  const double *x = p.x, *y = p.y, *vx = p.vx, *vy = p.vy, *w = p.w, *r = p.r;
  const std::int32_t *li = in.li, *lj = in.lj, *on = in.on;
  const double *ldn = in.dn, *lds = in.ds;
  const double kn = in.params.kn, kt = in.params.kt, eta_n = in.params.eta_n,
               eta_t = in.params.eta_t, mu = in.params.mu;
  const double dtau = in.dtau;
  const std::int64_t count = in.count;
#pragma omp simd
  for (std::int64_t q = 0; q < count; ++q) {
    const std::int32_t s = on[q];
    const bool fresh = s < 0;
    const std::int32_t k = s ^ (s >> 31);  // ~s for a fresh contact
    const std::int32_t i = li[k], j = lj[k];
    const double px = x[j] - x[i], py = y[j] - y[i];
    const double R = r[i] + r[j];
    const double L2 = px * px + py * py;
    const double Lc = std::sqrt(L2);
    const double nx = px / Lc, ny = py / Lc;
    const double tx = -ny, ty = nx;
    const double vrx = vx[i] - vx[j], vry = vy[i] - vy[j];
    const double vn = vrx * nx + vry * ny;
    const double vt = vrx * tx + vry * ty + w[i] * r[i] + w[j] * r[j];
    // Eq 13 (time_since_touch with w = -v_r), for every pair and kept for the fresh ones.
    const double wx = -vrx, wy = -vry;
    const double ww = wx * wx + wy * wy;
    const double pw = px * wx + py * wy;
    const double disc = pw * pw + ww * (R * R - Lc * Lc);
    // Computed for every lane and then chosen (a division under a condition would not vectorise).
    const double since_raw = (pw + std::sqrt(std::max(disc, 0.0))) / ww;
    const double since = ww <= 0.0 ? 0.0 : since_raw;
    const double tau = (fresh & Incremental) ? std::min(since, dtau) : dtau;
    const double dn = Incremental ? ldn[k] + vn * tau : R - Lc;  // eqs 14, 16
    const double ds_before = lds[k] + vt * tau;                  // eqs 15, 17
    // contact_force and contact_loss, branch-free.
    const double fn_spring = -kn * std::max(dn, 0.0);  // eq 3
    const double fn = fn_spring - eta_n * vn;          // eq 6
    const double ft_spring = -kt * ds_before;          // eq 4
    const double limit = mu * std::fabs(fn_spring);    // eq 5
    const bool sliding = std::fabs(ft_spring) > limit;
    const double ft_slide = ft_spring > 0.0 ? limit : -limit;
    const double ft = sliding ? ft_slide : ft_spring - eta_t * vt;  // eq 7
    const double ds_held = -ft / kt;  // the spring held at the limit (kt = 0: none)
    const double ds = (sliding & (kt > 0.0)) ? ds_held : ds_before;
    const double dash_n = eta_n * vn * vn * dtau;
    out.dashpot[q] = sliding ? dash_n : dash_n + eta_t * vt * vt * dtau;
    out.friction[q] = sliding ? std::fabs(ft) * std::fabs(ds_before - ds) : 0.0;
    out.dn[q] = dn;
    out.ds[q] = ds;
    out.fx[q] = fn * nx + ft * tx;
    out.fy[q] = fn * ny + ft * ty;
    out.ft[q] = ft;
    out.ratio[q] = 1.0 - Lc / R;
    out.sliding[q] = sliding;
  }
}

// Both forms, the choice outside the loops (the builds for one instruction set each).
__attribute__((always_inline)) inline void contacts_either(const PairContactIn& in,
                                                           const PairContactOut& out) {
  if (in.incremental) {
    contacts_loop<true>(in, out);
  } else {
    contacts_loop<false>(in, out);
  }
}

FLUIDBED_SIMD_CLONES void contacts_incremental(const PairContactIn& in, const PairContactOut& out) {
  contacts_loop<true>(in, out);
}

FLUIDBED_SIMD_CLONES void contacts_geometric(const PairContactIn& in, const PairContactOut& out) {
  contacts_loop<false>(in, out);
}

// Each instruction set's own build.
FLUIDBED_SIMD_AVX512F void classify_avx512f(const PairKernelParticles& p, const std::int32_t* li,
                                            const std::int32_t* lj, std::int64_t k0,
                                            std::int64_t k1, std::uint8_t* code) {
  classify_loop(p, li, lj, k0, k1, code);
}
FLUIDBED_SIMD_AVX2 void classify_avx2(const PairKernelParticles& p, const std::int32_t* li,
                                      const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                                      std::uint8_t* code) {
  classify_loop(p, li, lj, k0, k1, code);
}
void classify_baseline(const PairKernelParticles& p, const std::int32_t* li, const std::int32_t* lj,
                       std::int64_t k0, std::int64_t k1, std::uint8_t* code) {
  classify_loop(p, li, lj, k0, k1, code);
}

// The thick slab's classify: the distance in 3D, dot(p, p) in its order.
__attribute__((always_inline)) inline void classify_depth_loop(const DepthKernelParticles& p,
                                                               const std::int32_t* li,
                                                               const std::int32_t* lj,
                                                               std::int64_t k0, std::int64_t k1,
                                                               std::uint8_t* code) {
  const double *x = p.x, *y = p.y, *z = p.z, *r = p.r;
#pragma omp simd
  for (std::int64_t k = k0; k < k1; ++k) {
    const std::int32_t i = li[k], j = lj[k];
    const double px = x[j] - x[i], py = y[j] - y[i], pz = z[j] - z[i];
    const double R = r[i] + r[j];
    const double L2 = px * px + py * py + pz * pz;
    const int coincident = L2 <= 0.0;
    const int touching = (L2 < R * R) & (coincident ^ 1);
    code[k - k0] = static_cast<std::uint8_t>(touching | (coincident << 1));
  }
}

// DemSolver::pair_pass_depth's contact, branch-free: eq 13 for a fresh contact, the displacements
// (eqs 14-17), contact_force_3d (the shear vector turned into the contact plane, then advanced;
// the Coulomb cap along it) and rolling_torque_3d, each value as the scalar code computes it and
// a branch's two sides both computed, then chosen (the side not taken may divide by zero: its
// result is dropped). One loop per displacement form, per rolling resistance, on or off, and per
// law (Hertz-Mindlin: each contact's springs and dashpots from its overlap, as hertz_params).
template <bool Incremental, bool Rolling, bool Hertz>
__attribute__((always_inline)) inline void depth_loop(const DepthContactIn& in,
                                                      const DepthContactOut& out) {
  const DepthKernelParticles& p = in.p;
  const double *x = p.x, *y = p.y, *z = p.z, *vx = p.vx, *vy = p.vy, *vz = p.vz;
  const double *wx = p.wx, *wy = p.wy, *wz = p.wz, *r = p.r, *inv_i = p.inv_inertia;
  const double* mass = p.mass;
  const std::int32_t *li = in.li, *lj = in.lj, *on = in.on;
  const double *ldn = in.dn, *lds = in.ds, *lds_y = in.ds_y, *lds_z = in.ds_z;
  const double kn0 = in.params.kn, kt0 = in.params.kt, eta_n0 = in.params.eta_n,
               eta_t0 = in.params.eta_t, mu = in.params.mu, mu_r = in.params.mu_r;
  const double hz_kn = in.params.hertz_kn, hz_kt = in.params.hertz_kt,
               hz_damping = in.params.hertz_damping;
  const double dtau = in.dtau, hold_k0 = -1.0 / kt0;
  const std::int64_t count = in.count;
#pragma omp simd
  for (std::int64_t q = 0; q < count; ++q) {
    const bool fresh = on[q] < 0;  // listed as ~k
    const std::int32_t k = listed_slot(on[q]), i = li[k], j = lj[k];
    const double px = x[j] - x[i], py = y[j] - y[i], pz = z[j] - z[i];
    const double R = r[i] + r[j];
    const double L2 = px * px + py * py + pz * pz;
    const double Lc = std::sqrt(L2);
    const double inv_L = 1.0 / Lc;
    const double nx = inv_L * px, ny = inv_L * py, nz = inv_L * pz;
    const double spx = r[i] * wx[i] + r[j] * wx[j], spy = r[i] * wy[i] + r[j] * wy[j],
                 spz = r[i] * wz[i] + r[j] * wz[j];
    const double relx = vx[i] - vx[j], rely = vy[i] - vy[j], relz = vz[i] - vz[j];
    const double vrx = relx + (spy * nz - spz * ny), vry = rely + (spz * nx - spx * nz),
                 vrz = relz + (spx * ny - spy * nx);
    // Eq 13 (time_since_touch with w = -v_rel), for every pair and kept for the fresh ones.
    const double ux = -relx, uy = -rely, uz = -relz;
    const double ww = ux * ux + uy * uy + uz * uz;
    const double pw = px * ux + py * uy + pz * uz;
    const double disc = pw * pw + ww * (R * R - Lc * Lc);
    const double since_raw = (pw + std::sqrt(std::max(disc, 0.0))) / ww;
    const double since = ww <= 0.0 ? 0.0 : since_raw;
    const double tau = (fresh & Incremental) ? std::min(since, dtau) : dtau;
    const double vn = vrx * nx + vry * ny + vrz * nz;
    const double dn = Incremental ? ldn[k] + vn * tau : R - Lc;  // eqs 14, 16
    const double vtx = vrx - vn * nx, vty = vry - vn * ny, vtz = vrz - vn * nz;
    // The shear vector into the contact plane at its former length (when it has one).
    const double s0x = lds[k], s0y = lds_y[k], s0z = lds_z[k];
    const double s_len2 = s0x * s0x + s0y * s0y + s0z * s0z;
    const double sn = s0x * nx + s0y * ny + s0z * nz;
    const double ipx = s0x - sn * nx, ipy = s0y - sn * ny, ipz = s0z - sn * nz;
    const double p_len2 = ipx * ipx + ipy * ipy + ipz * ipz;
    const double scale = std::sqrt(s_len2 / p_len2);
    const bool turn = s_len2 > 0.0, in_plane = p_len2 > 0.0;
    const double s1x = turn ? (in_plane ? scale * ipx : 0.0) : s0x;
    const double s1y = turn ? (in_plane ? scale * ipy : 0.0) : s0y;
    const double s1z = turn ? (in_plane ? scale * ipz : 0.0) : s0z;
    const double sbx = s1x + tau * vtx, sby = s1y + tau * vty, sbz = s1z + tau * vtz;  // eqs 15, 17
    double kn = kn0, kt = kt0, eta_n = eta_n0, eta_t = eta_t0, hold_k = hold_k0;
    if constexpr (Hertz) {  // hertz_params with R* = R_i R_j / (R_i + R_j), m* = m_i m_j / (m_i + m_j)
      const double m_eff = mass[i] * mass[j] / (mass[i] + mass[j]);
      const double a = std::sqrt(r[i] * r[j] / R * std::max(dn, 0.0));
      kn = hz_kn * a;
      kt = hz_kt * a;
      eta_n = hz_damping * std::sqrt(1.5 * kn * m_eff);
      eta_t = hz_damping * std::sqrt(kt * m_eff);
      hold_k = -1.0 / kt;
    }
    const double fn_spring = -kn * std::max(dn, 0.0);                                  // eq 3
    const double fn = fn_spring - eta_n * vn;                                          // eq 6
    const double fsx = -kt * sbx, fsy = -kt * sby, fsz = -kt * sbz;                    // eq 4
    const double limit = mu * std::fabs(fn_spring);                                    // eq 5
    const double spring_len = std::sqrt(fsx * fsx + fsy * fsy + fsz * fsz);
    const bool sliding = spring_len > limit;
    const double cap = limit / spring_len;
    const double ftx = sliding ? cap * fsx : fsx - eta_t * vtx;  // eq 7
    const double fty = sliding ? cap * fsy : fsy - eta_t * vty;
    const double ftz = sliding ? cap * fsz : fsz - eta_t * vtz;
    const bool held = sliding & (kt > 0.0);  // the spring held at the limit (kt = 0: none)
    const double sax = held ? hold_k * ftx : sbx, say = held ? hold_k * fty : sby,
                 saz = held ? hold_k * ftz : sbz;
    const double slx = sbx - sax, sly = sby - say, slz = sbz - saz;
    const double dash_n = eta_n * vn * vn * dtau;
    double friction = sliding ? limit * std::sqrt(slx * slx + sly * sly + slz * slz) : 0.0;
    out.dashpot[q] = sliding ? dash_n : dash_n + eta_t * (vtx * vtx + vty * vty + vtz * vtz) * dtau;
    out.dn[q] = dn;
    out.ds[q] = sax;
    out.ds_y[q] = say;
    out.ds_z[q] = saz;
    out.fx[q] = fn * nx + ftx;
    out.fy[q] = fn * ny + fty;
    out.fz[q] = fn * nz + ftz;
    out.lever_x[q] = ny * ftz - nz * fty;  // cross(n, ft)
    out.lever_y[q] = nz * ftx - nx * ftz;
    out.lever_z[q] = nx * fty - ny * ftx;
    double rx = 0.0, ry = 0.0, rz = 0.0;
    if constexpr (Rolling) {  // rolling_torque_3d against w_rel, with rolling_torque's cap
      const double wrx = wx[i] - wx[j], wry = wy[i] - wy[j], wrz = wz[i] - wz[j];
      const double w2 = wrx * wrx + wry * wry + wrz * wrz;
      const double spin = std::sqrt(w2);
      const double stop = std::fabs(spin) / (dtau * (inv_i[i] + inv_i[j]));
      const double m = std::min(mu_r * (r[i] * r[j] / R) * std::fabs(fn_spring), stop);
      const double signed_m = spin > 0.0 ? -m : (spin < 0.0 ? m : 0.0);
      const double per_spin = signed_m / spin;
      const bool still = spin <= 0.0;
      rx = still ? 0.0 : per_spin * wrx;
      ry = still ? 0.0 : per_spin * wry;
      rz = still ? 0.0 : per_spin * wrz;
      friction += std::sqrt((rx * rx + ry * ry + rz * rz) * w2) * dtau;
    }
    out.roll_x[q] = rx;
    out.roll_y[q] = ry;
    out.roll_z[q] = rz;
    out.friction[q] = friction;
    out.ratio[q] = 1.0 - Lc / R;
    out.sliding[q] = sliding;
  }
}

// The eight forms, the choice outside the loops.
__attribute__((always_inline)) inline void depth_either(const DepthContactIn& in,
                                                        const DepthContactOut& out) {
  const bool rolling = in.params.mu_r > 0.0;
  if (in.params.hertz) {
    if (in.incremental) {
      if (rolling) {
        depth_loop<true, true, true>(in, out);
      } else {
        depth_loop<true, false, true>(in, out);
      }
    } else if (rolling) {
      depth_loop<false, true, true>(in, out);
    } else {
      depth_loop<false, false, true>(in, out);
    }
  } else if (in.incremental) {
    if (rolling) {
      depth_loop<true, true, false>(in, out);
    } else {
      depth_loop<true, false, false>(in, out);
    }
  } else if (rolling) {
    depth_loop<false, true, false>(in, out);
  } else {
    depth_loop<false, false, false>(in, out);
  }
}

FLUIDBED_SIMD_AVX512F void classify_depth_avx512f(const DepthKernelParticles& p,
                                                  const std::int32_t* li, const std::int32_t* lj,
                                                  std::int64_t k0, std::int64_t k1,
                                                  std::uint8_t* code) {
  classify_depth_loop(p, li, lj, k0, k1, code);
}
FLUIDBED_SIMD_AVX2 void classify_depth_avx2(const DepthKernelParticles& p, const std::int32_t* li,
                                            const std::int32_t* lj, std::int64_t k0,
                                            std::int64_t k1, std::uint8_t* code) {
  classify_depth_loop(p, li, lj, k0, k1, code);
}
void classify_depth_baseline(const DepthKernelParticles& p, const std::int32_t* li,
                             const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                             std::uint8_t* code) {
  classify_depth_loop(p, li, lj, k0, k1, code);
}

}  // namespace

FLUIDBED_SIMD_CLONES void classify_pairs_depth(const DepthKernelParticles& p,
                                               const std::int32_t* li, const std::int32_t* lj,
                                               std::int64_t k0, std::int64_t k1,
                                               std::uint8_t* code) {
  classify_depth_loop(p, li, lj, k0, k1, code);
}

FLUIDBED_SIMD_CLONES void depth_contacts(const DepthContactIn& in, const DepthContactOut& out) {
  depth_either(in, out);
}

void classify_pairs_depth_on(SimdBuild b, const DepthKernelParticles& p, const std::int32_t* li,
                             const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                             std::uint8_t* code) {
  call_build(b, classify_depth_avx512f, classify_depth_avx2, classify_depth_baseline, p, li, lj, k0,
             k1, code);
}

void depth_contacts_on(SimdBuild b, const DepthContactIn& in, const DepthContactOut& out) {
  call_contacts_build<depth_either>(b, in, out);
}

FLUIDBED_SIMD_CLONES void classify_pairs(const PairKernelParticles& p, const std::int32_t* li,
                                         const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                                         std::uint8_t* code) {
  classify_loop(p, li, lj, k0, k1, code);
}

void pair_contacts(const PairContactIn& in, const PairContactOut& out) {
  if (in.incremental) {
    contacts_incremental(in, out);
  } else {
    contacts_geometric(in, out);
  }
}

void classify_pairs_on(SimdBuild b, const PairKernelParticles& p, const std::int32_t* li,
                       const std::int32_t* lj, std::int64_t k0, std::int64_t k1,
                       std::uint8_t* code) {
  call_build(b, classify_avx512f, classify_avx2, classify_baseline, p, li, lj, k0, k1, code);
}

void pair_contacts_on(SimdBuild b, const PairContactIn& in, const PairContactOut& out) {
  call_contacts_build<contacts_either>(b, in, out);
}

}  // namespace fluidbed
