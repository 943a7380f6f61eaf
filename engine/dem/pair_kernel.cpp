#include "dem/pair_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "core/simd.hpp"

namespace fluidbed {

namespace {

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

}  // namespace

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
