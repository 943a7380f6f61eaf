// A thick slab's kernels (dem/pair_kernel.hpp): which pairs touch in 3D, the contact law of
// contact_force_3d with the rolling resistance of rolling_torque_3d for the touching pairs, and
// the same law for the contacts of spheres with the walls. Branch-free, so that the compiler
// handles several contacts at a time, and in the scalar law's operations and order, so that every
// build (AVX-512, AVX2, plain x86-64) gives the scalar law's bits.
#include <algorithm>
#include <cmath>

#include "core/simd.hpp"
#include "dem/pair_kernel.hpp"

namespace fluidbed {

namespace {

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

// A contact's springs and dashpots, and -1 / kt (the factor that holds a sliding spring at the
// Coulomb limit).
struct Springs {
  double kn, kt, eta_n, eta_t, hold_k;
};
inline Springs linear_springs(const ContactParams& p) {
  return {p.kn, p.kt, p.eta_n, p.eta_t, -1.0 / p.kt};
}
// Hertz-Mindlin's, as hertz_params computes them, for the effective radius and mass.
__attribute__((always_inline)) inline Springs hertz_springs(const ContactParams& p, double dn,
                                                            double r_eff, double m_eff) {
  const double a = std::sqrt(r_eff * std::max(dn, 0.0));
  const double kn = p.hertz_kn * a, kt = p.hertz_kt * a;
  return {kn, kt, p.hertz_damping * std::sqrt(1.5 * kn * m_eff),
          p.hertz_damping * std::sqrt(kt * m_eff), -1.0 / kt};
}

// contact_force_3d and rolling_torque_3d, branch-free, into contact q of out: for the unit normal
// n (from i into its partner), the contact point's relative velocity vr with vn = vr . n, the
// normal displacement dn (advanced), the shear vector s0 carried from the last step (advanced over
// tau), the springs k, friction mu; with rolling resistance, mu_r against the relative spin w
// with the effective radius r_roll and the inverse inertias' sum; the losses over dtau.
struct Contact3 {
  double nx, ny, nz, vrx, vry, vrz, vn, dn, s0x, s0y, s0z, tau;
};
struct Rolling3 {
  double r_roll, wx, wy, wz, inv_inertia_sum;
};
template <bool Rolling>
__attribute__((always_inline)) inline void law_3d(const DepthContactOut& out, std::int64_t q,
                                                  const Contact3& c, const Springs& k, double mu,
                                                  double mu_r, const Rolling3& w, double dtau,
                                                  double ratio) {
  const double nx = c.nx, ny = c.ny, nz = c.nz, vn = c.vn, tau = c.tau;
  const double vtx = c.vrx - vn * nx, vty = c.vry - vn * ny, vtz = c.vrz - vn * nz;
  // The shear vector into the contact plane at its former length (when it has one).
  const double s0x = c.s0x, s0y = c.s0y, s0z = c.s0z;
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
  const double fn_spring = -k.kn * std::max(c.dn, 0.0);                              // eq 3
  const double fn = fn_spring - k.eta_n * vn;                                        // eq 6
  const double fsx = -k.kt * sbx, fsy = -k.kt * sby, fsz = -k.kt * sbz;              // eq 4
  const double limit = mu * std::fabs(fn_spring);                                    // eq 5
  const double spring_len = std::sqrt(fsx * fsx + fsy * fsy + fsz * fsz);
  const bool sliding = spring_len > limit;
  const double cap = limit / spring_len;
  const double ftx = sliding ? cap * fsx : fsx - k.eta_t * vtx;  // eq 7
  const double fty = sliding ? cap * fsy : fsy - k.eta_t * vty;
  const double ftz = sliding ? cap * fsz : fsz - k.eta_t * vtz;
  const bool held = sliding & (k.kt > 0.0);  // the spring held at the limit (kt = 0: none)
  const double sax = held ? k.hold_k * ftx : sbx, say = held ? k.hold_k * fty : sby,
               saz = held ? k.hold_k * ftz : sbz;
  const double slx = sbx - sax, sly = sby - say, slz = sbz - saz;
  const double dash_n = k.eta_n * vn * vn * dtau;
  double friction = sliding ? limit * std::sqrt(slx * slx + sly * sly + slz * slz) : 0.0;
  out.dashpot[q] = sliding ? dash_n : dash_n + k.eta_t * (vtx * vtx + vty * vty + vtz * vtz) * dtau;
  out.dn[q] = c.dn;
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
  if constexpr (Rolling) {  // rolling_torque_3d against w, with rolling_torque's cap
    const double w2 = w.wx * w.wx + w.wy * w.wy + w.wz * w.wz;
    const double spin = std::sqrt(w2);
    const double stop = std::fabs(spin) / (dtau * w.inv_inertia_sum);
    const double m = std::min(mu_r * w.r_roll * std::fabs(fn_spring), stop);
    const double signed_m = spin > 0.0 ? -m : (spin < 0.0 ? m : 0.0);
    const double per_spin = signed_m / spin;
    const bool still = spin <= 0.0;
    rx = still ? 0.0 : per_spin * w.wx;
    ry = still ? 0.0 : per_spin * w.wy;
    rz = still ? 0.0 : per_spin * w.wz;
    friction += std::sqrt((rx * rx + ry * ry + rz * rz) * w2) * dtau;
  }
  out.roll_x[q] = rx;
  out.roll_y[q] = ry;
  out.roll_z[q] = rz;
  out.friction[q] = friction;
  out.ratio[q] = ratio;
  out.sliding[q] = sliding;
}

// DemSolver::pair_pass_depth's contact, branch-free: eq 13 for a fresh contact, the displacements
// (eqs 14-17), contact_force_3d (the shear vector turned into the contact plane, then advanced;
// the Coulomb cap along it) and rolling_torque_3d, each value as the scalar code computes it and
// a branch's two sides both computed, then chosen (the side not taken may divide by zero: its
// result is dropped). One loop per displacement form, per rolling resistance, on or off, and per
// law (Hertz-Mindlin: each contact's springs and dashpots from its overlap, as hertz_params).
struct PairLoops {
  template <bool Incremental, bool Rolling, bool Hertz>
  __attribute__((always_inline)) static void run(const DepthContactIn& in,
                                                 const DepthContactOut& out) {
    const DepthKernelParticles& p = in.p;
    const double *x = p.x, *y = p.y, *z = p.z, *vx = p.vx, *vy = p.vy, *vz = p.vz;
    const double *wx = p.wx, *wy = p.wy, *wz = p.wz, *r = p.r, *inv_i = p.inv_inertia;
    const double* mass = p.mass;
    const std::int32_t *li = in.li, *lj = in.lj, *on = in.on;
    const double *ldn = in.dn, *lds = in.ds, *lds_y = in.ds_y, *lds_z = in.ds_z;
    const auto [kn, kt, eta_n, eta_t, hold_k] = linear_springs(in.params);
    const double mu = in.params.mu, mu_r = in.params.mu_r, dtau = in.dtau;
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
      // Hertz-Mindlin: R* = R_i R_j / (R_i + R_j), m* = m_i m_j / (m_i + m_j).
      const Springs springs = Hertz ? hertz_springs(in.params, dn, r[i] * r[j] / R,
                                                    mass[i] * mass[j] / (mass[i] + mass[j]))
                                    : Springs{kn, kt, eta_n, eta_t, hold_k};
      law_3d<Rolling>(
          out, q, {nx, ny, nz, vrx, vry, vrz, vn, dn, lds[k], lds_y[k], lds_z[k], tau}, springs, mu,
          mu_r, {r[i] * r[j] / R, wx[i] - wx[j], wy[i] - wy[j], wz[i] - wz[j], inv_i[i] + inv_i[j]},
          dtau, 1.0 - Lc / R);
    }
  }
};

// DemSolver::particle_pass_depth's contact of sphere i with wall c (n the wall's inward normal
// reversed: from the sphere into the wall; the wall at rest), branch-free as PairLoops: the
// velocity of the contact point v_i + R_i w_i x n, time_since_touch_wall for a fresh contact,
// the law with R* = R_i and m* = m_i, the rolling resistance against the sphere's spin.
struct WallLoops {
  template <bool Incremental, bool Rolling, bool Hertz>
  __attribute__((always_inline)) static void run(const WallContactIn& in,
                                                 const DepthContactOut& out) {
    const DepthKernelParticles& p = in.p;
    const double *x = p.x, *y = p.y, *z = p.z, *vx = p.vx, *vy = p.vy, *vz = p.vz;
    const double *wx = p.wx, *wy = p.wy, *wz = p.wz, *r = p.r, *inv_i = p.inv_inertia;
    const double* mass = p.mass;
    const std::int32_t *on = in.on, *particle = in.particle;
    const double *wall_nx = in.nx, *wall_ny = in.ny, *wall_nz = in.nz, *wall_off = in.offset;
    const double *hdn = in.dn, *hds = in.ds, *hds_y = in.ds_y, *hds_z = in.ds_z;
    const auto [kn, kt, eta_n, eta_t, hold_k] = linear_springs(in.params);
    const double mu = in.params.mu, mu_r = in.params.mu_r, dtau = in.dtau;
    const std::int32_t walls = in.walls;
    const std::int64_t count = in.count;
#pragma omp simd
    for (std::int64_t q = 0; q < count; ++q) {
      const bool fresh = on[q] < 0;  // listed as ~s
      const std::int32_t s = listed_slot(on[q]), i = particle[q], c = s - i * walls;
      const double d = wall_nx[c] * x[i] + wall_ny[c] * y[i] + wall_nz[c] * z[i] - wall_off[c];
      const double nx = -wall_nx[c], ny = -wall_ny[c], nz = -wall_nz[c];
      const double overlap = r[i] - d;
      const double cx = wy[i] * nz - wz[i] * ny, cy = wz[i] * nx - wx[i] * nz,
                   cz = wx[i] * ny - wy[i] * nx;  // cross(w_i, n)
      const double vrx = vx[i] + r[i] * cx, vry = vy[i] + r[i] * cy, vrz = vz[i] + r[i] * cz;
      const double vn = vrx * nx + vry * ny + vrz * nz;
      const double since = vn > 0.0 ? overlap / vn : 0.0;  // time_since_touch_wall
      const double tau = (fresh & Incremental) ? std::min(since, dtau) : dtau;
      const double dn = Incremental ? hdn[s] + vn * tau : overlap;
      const Springs springs = Hertz ? hertz_springs(in.params, dn, r[i], mass[i])
                                    : Springs{kn, kt, eta_n, eta_t, hold_k};
      law_3d<Rolling>(out, q, {nx, ny, nz, vrx, vry, vrz, vn, dn, hds[s], hds_y[s], hds_z[s], tau},
                      springs, mu, mu_r, {r[i], wx[i], wy[i], wz[i], inv_i[i]}, dtau,
                      overlap / r[i]);
    }
  }
};

// The four forms of a kernel's loops for one law (Hertz or linear), the choice outside the loops.
template <class Loops, bool Hertz, class In>
__attribute__((always_inline)) inline void four_forms(const In& in, const DepthContactOut& out) {
  const bool rolling = in.params.mu_r > 0.0;
  if (in.incremental) {
    if (rolling) {
      Loops::template run<true, true, Hertz>(in, out);
    } else {
      Loops::template run<true, false, Hertz>(in, out);
    }
  } else if (rolling) {
    Loops::template run<false, true, Hertz>(in, out);
  } else {
    Loops::template run<false, false, Hertz>(in, out);
  }
}

// The eight forms: the law's four each.
template <class Loops, class In>
__attribute__((always_inline)) inline void eight_forms(const In& in, const DepthContactOut& out) {
  if (in.params.hertz) {
    four_forms<Loops, true>(in, out);
  } else {
    four_forms<Loops, false>(in, out);
  }
}
__attribute__((always_inline)) inline void depth_either(const DepthContactIn& in,
                                                        const DepthContactOut& out) {
  eight_forms<PairLoops>(in, out);
}
__attribute__((always_inline)) inline void wall_either(const WallContactIn& in,
                                                       const DepthContactOut& out) {
  eight_forms<WallLoops>(in, out);
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

FLUIDBED_SIMD_CLONES void wall_contacts_depth(const WallContactIn& in, const DepthContactOut& out) {
  wall_either(in, out);
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

void wall_contacts_depth_on(SimdBuild b, const WallContactIn& in, const DepthContactOut& out) {
  call_contacts_build<wall_either>(b, in, out);
}

}  // namespace fluidbed
