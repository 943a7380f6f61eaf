// The particle solver's branch-free pair kernels (dem/pair_kernel.hpp) against the scalar contact
// law (dem/contact_law.hpp): every build of them (AVX-512, AVX2 and plain x86-64, whichever this
// CPU runs; core/simd.hpp) gives the scalar law's bits on random pairs, touching or not.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "core/simd.hpp"
#include "dem/contact_law.hpp"
#include "dem/pair_kernel.hpp"

using fluidbed::ContactParams;
using fluidbed::SimdBuild;

namespace {

// Random pairs of particles 2q and 2q + 1 (the kernels want li < lj): centres at 0.2 to 1.3 times
// the sum of the radii apart in any direction (touching or not), a few at the sum to rounding and
// a few coincident, with random velocities, spins and carried history.
struct KernelPairs {
  std::vector<double> x, y, vx, vy, w, r;
  std::vector<std::int32_t> li, lj;
  std::vector<double> dn, ds;  // the slots' history
  // The pairs with distinct centres, as the contact kernel takes them: slot k, or ~k for a
  // contact that is new (about 30 %).
  std::vector<std::int32_t> on;

  fluidbed::PairKernelParticles particles() const {
    return {x.data(), y.data(), vx.data(), vy.data(), w.data(), r.data()};
  }
};

// Pair q's radii (1 to 3 mm) and the distance of its centres: 0.2 to 1.3 times the sum of the
// radii, or the sum to rounding for every 97th pair. direction() draws the direction between the
// radii and the distance (the generators' order of draws).
struct PairDraw {
  double ri, rj, L;
};
template <class Direction>
PairDraw draw_pair(std::mt19937_64& rng, std::size_t q, Direction direction) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double ri = 0.001 + 0.002 * u(rng), rj = 0.001 + 0.002 * u(rng);
  direction();
  const double R = ri + rj, L = R * (0.2 + 1.1 * u(rng));
  return {ri, rj, q % 97 == 5 ? R : L};
}

KernelPairs random_pairs(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  KernelPairs s;
  for (std::size_t q = 0; q < n; ++q) {
    double a = 0.0;
    const auto [ri, rj, L] = draw_pair(rng, q, [&] { a = 2.0 * std::numbers::pi * u(rng); });
    const double x0 = 0.15 * u(rng), y0 = 0.9 * u(rng);
    const double x1 = q % 89 == 7 ? x0 : x0 + L * std::cos(a);  // coincident centres
    const double y1 = q % 89 == 7 ? y0 : y0 + L * std::sin(a);
    s.x.insert(s.x.end(), {x0, x1});
    s.y.insert(s.y.end(), {y0, y1});
    s.r.insert(s.r.end(), {ri, rj});
    for (int k = 0; k < 2; ++k) {
      // Some at rest relative to each other (eq 13's zero relative velocity).
      const bool rest = q % 31 == 3;
      s.vx.push_back(rest ? 0.25 : 4.0 * u(rng) - 2.0);
      s.vy.push_back(rest ? -0.5 : 4.0 * u(rng) - 2.0);
      s.w.push_back(rest ? 0.0 : 1000.0 * u(rng) - 500.0);
    }
    s.li.push_back(static_cast<std::int32_t>(2 * q));
    s.lj.push_back(static_cast<std::int32_t>(2 * q + 1));
    // History from a few steps of contact: sticking and sliding both occur.
    s.dn.push_back(1.2e-4 * u(rng) - 2e-5);
    s.ds.push_back(2e-4 * u(rng) - 1e-4);
    const auto k = static_cast<std::int32_t>(q);
    if (q % 89 != 7) s.on.push_back(u(rng) < 0.3 ? ~k : k);
  }
  return s;
}

std::uint64_t bits_of(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

// The kernel's outputs for one contact.
struct KernelContact {
  double dn, ds, fx, fy, ft, ratio, dashpot, friction;
  std::int32_t sliding;
};

// Contact q of the kernel's pass, from the scalar law: eq 13 for a new contact with the
// incremental displacements, eqs 14-17, contact_force, contact_loss.
KernelContact scalar_contact(const KernelPairs& s, std::int32_t slot, const ContactParams& p,
                             bool incremental, double dtau) {
  const bool fresh = slot < 0;
  const std::int32_t k = fresh ? ~slot : slot;
  const std::int32_t i = s.li[k], j = s.lj[k];
  const double px = s.x[j] - s.x[i], py = s.y[j] - s.y[i];
  const double R = s.r[i] + s.r[j];
  const double L = std::sqrt(px * px + py * py);
  const double nx = px / L, ny = py / L, tx = -ny, ty = nx;
  const double vrx = s.vx[i] - s.vx[j], vry = s.vy[i] - s.vy[j];
  const double vn = vrx * nx + vry * ny;
  const double vt = vrx * tx + vry * ty + s.w[i] * s.r[i] + s.w[j] * s.r[j];
  // The caller clears a new contact's history.
  const double dn0 = fresh ? 0.0 : s.dn[k], ds0 = fresh ? 0.0 : s.ds[k];
  const double tau = fresh && incremental
                         ? std::min(fluidbed::time_since_touch(px, py, -vrx, -vry, R, L), dtau)
                         : dtau;
  const double dn = incremental ? dn0 + vn * tau : R - L;
  const double ds_before = ds0 + vt * tau;
  double ds = ds_before;
  const fluidbed::ContactForce f = fluidbed::contact_force(p, dn, ds, vn, vt);
  const fluidbed::ContactLoss loss = fluidbed::contact_loss(p, f, ds_before, ds, vn, vt, dtau);
  return {dn,          ds,           f.fn * nx + f.ft * tx, f.fn * ny + f.ft * ty, f.ft,
          1.0 - L / R, loss.dashpot, loss.friction,         f.sliding ? 1 : 0};
}

// Every build of a classify kernel (classify(b, code) for slots [k0, n)) against want(k), the
// scalar test's code of slot k; then the build the loader chose (chosen(code)) against the
// baseline. The sample must hold all three kinds.
template <class Classify, class Chosen, class Want>
void expect_codes_of_every_build(std::int64_t k0, std::int64_t n, Classify classify, Chosen chosen,
                                 Want want) {
  int touching = 0, apart = 0, coincident = 0;
  const auto m = static_cast<std::size_t>(n - k0);
  for (SimdBuild b : fluidbed::kSimdBuilds) {
    if (!fluidbed::cpu_runs(b)) continue;
    SCOPED_TRACE(fluidbed::to_string(b));
    std::vector<std::uint8_t> code(m, 255);
    classify(b, code.data());
    for (std::int64_t k = k0; k < n; ++k) {
      const int w = want(k);
      ASSERT_EQ(code[static_cast<std::size_t>(k - k0)], w) << "pair " << k;
      touching += w == 1;
      apart += w == 0;
      coincident += w == 2;
    }
  }
  EXPECT_GT(touching, 1000);
  EXPECT_GT(apart, 100);
  EXPECT_GT(coincident, 10);
  std::vector<std::uint8_t> loaded(m), baseline(m);
  chosen(loaded.data());
  classify(SimdBuild::baseline, baseline.data());
  EXPECT_EQ(loaded, baseline);
}

// Calls check(b, law, incremental, dtau) for every build the CPU runs, every law and both
// displacement forms (with a step that differs by law); returns how many builds ran.
template <class Check>
int for_every_build_law_and_form(std::size_t laws, Check check) {
  int builds = 0;
  for (SimdBuild b : fluidbed::kSimdBuilds) {
    if (!fluidbed::cpu_runs(b)) continue;
    ++builds;
    SCOPED_TRACE(fluidbed::to_string(b));
    for (std::size_t law = 0; law < laws; ++law)
      for (const bool incremental : {true, false}) {
        SCOPED_TRACE(::testing::Message()
                     << "law " << law << (incremental ? ", incremental" : ", geometric"));
        check(b, law, incremental, 1.5e-5 * static_cast<double>(law + 1));
      }
  }
  return builds;
}

}  // namespace

// Which pairs touch: 1 closer than the sum of the radii, 2 for coincident centres, 0 otherwise
// (at exactly the sum too), from every build; the slots [k0, k1) of a range, not from 0.
TEST(PairKernel, EveryBuildClassifiesPairsAsTheScalarTest) {
  const KernelPairs s = random_pairs(4099, 1);
  const auto n = static_cast<std::int64_t>(s.li.size());
  const std::int64_t k0 = 3;
  expect_codes_of_every_build(
      k0, n,
      [&](SimdBuild b, std::uint8_t* code) {
        fluidbed::classify_pairs_on(b, s.particles(), s.li.data(), s.lj.data(), k0, n, code);
      },
      [&](std::uint8_t* code) {
        fluidbed::classify_pairs(s.particles(), s.li.data(), s.lj.data(), k0, n, code);
      },
      [&](std::int64_t k) {
        const std::int32_t i = s.li[k], j = s.lj[k];
        const double px = s.x[j] - s.x[i], py = s.y[j] - s.y[i];
        const double R = s.r[i] + s.r[j];
        const double L2 = px * px + py * py;
        return L2 <= 0.0 ? 2 : (L2 < R * R ? 1 : 0);
      });
}

// The contact kernel against contact_force and contact_loss to the bit (force, history, overlap
// ratio, losses, sliding), with the incremental displacements (eqs 13-15, new contacts' first
// increment from eq 13) and the geometric ones (eqs 16-17), for the paper's contact and for
// others: no tangential spring (kt = 0), no friction, no dashpots, a stiff spring. Pairs that
// touch and pairs that do not (the kernel is given only touching ones, but its arithmetic is
// the law's for any).
TEST(PairKernel, EveryBuildGivesTheScalarContactLawToTheBit) {
  const KernelPairs s = random_pairs(4099, 2);
  const std::vector<ContactParams> laws = {
      {50000.0, 50000.0, 0.15, 0.15, 0.3, 0.0},  // the paper's
      {50000.0, 0.0, 0.15, 0.15, 0.3, 0.0},      // no tangential spring
      {50000.0, 50000.0, 0.15, 0.15, 0.0, 0.0},  // frictionless
      {50000.0, 14285.7, 0.0, 0.0, 0.3, 0.0},    // undamped
      {1.0e6, 8.0e5, 2.5, 1.1, 0.45, 0.0},       // stiff
  };
  const auto count = static_cast<std::int64_t>(s.on.size());
  const auto n = static_cast<std::size_t>(count);
  int sliding = 0, sticking = 0, fresh = 0, apart = 0;
  const int builds = for_every_build_law_and_form(
      laws.size(), [&](SimdBuild b, std::size_t law, bool incremental, double dtau) {
        // History as the caller hands it: cleared for a new contact.
        std::vector<double> hdn = s.dn, hds = s.ds;
        for (std::int32_t slot : s.on)
          if (slot < 0)
            hdn[static_cast<std::size_t>(~slot)] = hds[static_cast<std::size_t>(~slot)] = 0.0;
        std::vector<double> dn(n, -1.0), ds(n, -1.0), fx(n, -1.0), fy(n, -1.0), ft(n, -1.0),
            ratio(n, -1.0), dashpot(n, -1.0), friction(n, -1.0);
        std::vector<std::int32_t> slides(n, -1);
        const fluidbed::PairContactOut out{dn.data(),      ds.data(),       fx.data(),
                                           fy.data(),      ft.data(),       ratio.data(),
                                           dashpot.data(), friction.data(), slides.data()};
        fluidbed::pair_contacts_on(b,
                                   {s.particles(), s.li.data(), s.lj.data(), hdn.data(), hds.data(),
                                    s.on.data(), count, laws[law], incremental, dtau},
                                   out);
        for (std::size_t q = 0; q < n; ++q) {
          const KernelContact want = scalar_contact(s, s.on[q], laws[law], incremental, dtau);
          ASSERT_EQ(bits_of(dn[q]), bits_of(want.dn)) << "contact " << q;
          ASSERT_EQ(bits_of(ds[q]), bits_of(want.ds)) << "contact " << q;
          ASSERT_EQ(bits_of(fx[q]), bits_of(want.fx)) << "contact " << q;
          ASSERT_EQ(bits_of(fy[q]), bits_of(want.fy)) << "contact " << q;
          ASSERT_EQ(bits_of(ft[q]), bits_of(want.ft)) << "contact " << q;
          ASSERT_EQ(bits_of(ratio[q]), bits_of(want.ratio)) << "contact " << q;
          ASSERT_EQ(bits_of(dashpot[q]), bits_of(want.dashpot)) << "contact " << q;
          ASSERT_EQ(bits_of(friction[q]), bits_of(want.friction)) << "contact " << q;
          ASSERT_EQ(slides[q], want.sliding) << "contact " << q;
          sliding += want.sliding;
          sticking += 1 - want.sliding;
          fresh += s.on[q] < 0;
          apart += want.ratio <= 0.0;
        }
      });
  EXPECT_GE(builds, 1);
  // The sample covers what the law tells apart.
  EXPECT_GT(sliding, 1000);
  EXPECT_GT(sticking, 1000);
  EXPECT_GT(fresh, 1000);
  EXPECT_GT(apart, 100);

  // The build the loader chose is one of them: the same bits as the baseline build.
  for (const bool incremental : {true, false}) {
    std::vector<double> a(8 * n), c(8 * n);
    std::vector<std::int32_t> sa(n), sc(n);
    const auto out_in = [n](std::vector<double>& v, std::vector<std::int32_t>& sl) {
      return fluidbed::PairContactOut{&v[0],     &v[n],     &v[2 * n], &v[3 * n], &v[4 * n],
                                      &v[5 * n], &v[6 * n], &v[7 * n], sl.data()};
    };
    const fluidbed::PairContactIn in{s.particles(), s.li.data(), s.lj.data(), s.dn.data(),
                                     s.ds.data(),   s.on.data(), count,       laws[0],
                                     incremental,   1.5e-5};
    fluidbed::pair_contacts(in, out_in(a, sa));
    fluidbed::pair_contacts_on(SimdBuild::baseline, in, out_in(c, sc));
    for (std::size_t k = 0; k < 8 * n; ++k)
      ASSERT_EQ(bits_of(a[k]), bits_of(c[k])) << "value " << k;
    EXPECT_EQ(sa, sc);
  }
}

namespace {

// Random pairs in three dimensions (a thick slab), as random_pairs: centres 0.2 to 1.3 times the
// sum of the radii apart in any direction, a few at the sum and a few coincident, random
// velocities and spins about every axis, and a carried shear vector: random (mostly off the
// contact plane, so that it is turned into it), zero, or along the normal (nothing left in the
// plane).
struct DepthPairs {
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz, r, inv_i, mass;
  std::vector<std::int32_t> li, lj;
  std::vector<double> dn, ds, ds_y, ds_z;
  std::vector<std::int32_t> on;

  fluidbed::DepthKernelParticles particles() const {
    return {x.data(),  y.data(),  z.data(),  vx.data(), vy.data(),    vz.data(),
            wx.data(), wy.data(), wz.data(), r.data(),  inv_i.data(), mass.data()};
  }
};

DepthPairs random_depth_pairs(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  DepthPairs s;
  for (std::size_t q = 0; q < n; ++q) {
    double ex = 0.0, ey = 0.0, ez = 0.0;  // a random direction
    const auto [ri, rj, L] = draw_pair(rng, q, [&] {
      const double a = 2.0 * std::numbers::pi * u(rng), c = 2.0 * u(rng) - 1.0;
      const double sc = std::sqrt(1.0 - c * c);
      ex = sc * std::cos(a);
      ey = sc * std::sin(a);
      ez = c;
    });
    const bool coincident = q % 89 == 7;
    const double x0 = 0.15 * u(rng), y0 = 0.9 * u(rng), z0 = 0.008 * u(rng);
    s.x.insert(s.x.end(), {x0, coincident ? x0 : x0 + L * ex});
    s.y.insert(s.y.end(), {y0, coincident ? y0 : y0 + L * ey});
    s.z.insert(s.z.end(), {z0, coincident ? z0 : z0 + L * ez});
    s.r.insert(s.r.end(), {ri, rj});
    for (double rad : {ri, rj}) {
      const bool rest = q % 31 == 3;  // no relative motion (eq 13's zero, no rolling)
      s.vx.push_back(rest ? 0.25 : 4.0 * u(rng) - 2.0);
      s.vy.push_back(rest ? -0.5 : 4.0 * u(rng) - 2.0);
      s.vz.push_back(rest ? 0.1 : 4.0 * u(rng) - 2.0);
      s.wx.push_back(rest ? 3.0 : 1000.0 * u(rng) - 500.0);
      s.wy.push_back(rest ? -2.0 : 1000.0 * u(rng) - 500.0);
      s.wz.push_back(rest ? 1.0 : 1000.0 * u(rng) - 500.0);
      const double m = 1150.0 * 4.0 / 3.0 * std::numbers::pi * rad * rad * rad;
      s.inv_i.push_back(1.0 / (0.4 * m * rad * rad));
      s.mass.push_back(m);
    }
    s.li.push_back(static_cast<std::int32_t>(2 * q));
    s.lj.push_back(static_cast<std::int32_t>(2 * q + 1));
    s.dn.push_back(1.2e-4 * u(rng) - 2e-5);
    const int kind = static_cast<int>(q % 11);
    if (kind == 0) {  // no shear yet
      s.ds.push_back(0.0);
      s.ds_y.push_back(0.0);
      s.ds_z.push_back(0.0);
    } else if (kind == 1) {  // along the normal: nothing in the plane
      const double d = 2e-4 * u(rng) - 1e-4;
      s.ds.push_back(d * ex);
      s.ds_y.push_back(d * ey);
      s.ds_z.push_back(d * ez);
    } else {
      s.ds.push_back(2e-4 * u(rng) - 1e-4);
      s.ds_y.push_back(2e-4 * u(rng) - 1e-4);
      s.ds_z.push_back(2e-4 * u(rng) - 1e-4);
    }
    const auto k = static_cast<std::int32_t>(q);
    if (!coincident) s.on.push_back(u(rng) < 0.3 ? ~k : k);
  }
  return s;
}

// dn, ds, ds_y, ds_z, fx, fy, fz, lever x y z, roll x y z, ratio, dashpot, friction; sliding.
struct DepthContact {
  std::array<double, 16> v;
  std::int32_t sliding;
};

// Contact q as DemSolver::pair_pass_depth computed it before the kernel: eq 13 for a new contact,
// eqs 14-17, contact_force_3d, rolling_torque_3d and its loss.
DepthContact scalar_depth_contact(const DepthPairs& s, std::int32_t slot, const ContactParams& p,
                                  bool incremental, double dtau) {
  using fluidbed::Vec3;
  const bool fresh = slot < 0;
  const std::int32_t k = fresh ? ~slot : slot;
  const std::int32_t i = s.li[k], j = s.lj[k];
  const Vec3 d{s.x[j] - s.x[i], s.y[j] - s.y[i], s.z[j] - s.z[i]};
  const double R = s.r[i] + s.r[j];
  const double Lc = std::sqrt(fluidbed::dot(d, d));
  const Vec3 n = (1.0 / Lc) * d;
  const Vec3 spin =
      s.r[i] * Vec3{s.wx[i], s.wy[i], s.wz[i]} + s.r[j] * Vec3{s.wx[j], s.wy[j], s.wz[j]};
  const Vec3 v_rel{s.vx[i] - s.vx[j], s.vy[i] - s.vy[j], s.vz[i] - s.vz[j]};
  const Vec3 vr = v_rel + fluidbed::cross(spin, n);
  double tau = dtau;
  if (fresh && incremental)
    tau = std::min(fluidbed::time_since_touch(d.x, d.y, -v_rel.x, -v_rel.y, R, Lc, d.z, -v_rel.z),
                   dtau);
  const double dn0 = fresh ? 0.0 : s.dn[k];
  Vec3 shear = fresh ? Vec3{} : Vec3{s.ds[k], s.ds_y[k], s.ds_z[k]};
  const double dn = incremental ? dn0 + fluidbed::dot(vr, n) * tau : R - Lc;
  const ContactParams law =
      p.hertz ? fluidbed::hertz_params(p, dn, s.r[i] * s.r[j] / R,
                                       s.mass[i] * s.mass[j] / (s.mass[i] + s.mass[j]))
              : p;
  fluidbed::ContactForce3 f = fluidbed::contact_force_3d(law, dn, shear, n, vr, tau, dtau);
  Vec3 roll;
  if (p.mu_r > 0.0) {
    const Vec3 w_rel{s.wx[i] - s.wx[j], s.wy[i] - s.wy[j], s.wz[i] - s.wz[j]};
    roll = fluidbed::rolling_torque_3d(p.mu_r, s.r[i] * s.r[j] / R, f.fn_spring, w_rel,
                                       s.inv_i[i] + s.inv_i[j], dtau);
    f.loss.friction += std::sqrt(fluidbed::dot(roll, roll) * fluidbed::dot(w_rel, w_rel)) * dtau;
  }
  return {{dn, shear.x, shear.y, shear.z, f.force.x, f.force.y, f.force.z, f.lever.x, f.lever.y,
           f.lever.z, roll.x, roll.y, roll.z, 1.0 - Lc / R, f.loss.dashpot, f.loss.friction},
          f.sliding ? 1 : 0};
}

// The kernel's outputs, one array per field in DepthContact's order.
struct DepthOutputs {
  std::vector<double> v;  // 16 fields of n
  std::vector<std::int32_t> sliding;
  std::size_t n;
  explicit DepthOutputs(std::size_t count) : v(16 * count, -1.0), sliding(count, -1), n(count) {}
  double* f(int field) { return &v[static_cast<std::size_t>(field) * n]; }
  fluidbed::DepthContactOut out() {
    return {f(0), f(1),  f(2),  f(3),  f(4),  f(5),  f(6),  f(7),          f(8),
            f(9), f(10), f(11), f(12), f(13), f(14), f(15), sliding.data()};
  }
};

}  // namespace

// The 3D kernels: which pairs touch, then the contact law against contact_force_3d and
// rolling_torque_3d to the bit (history with
// the turned shear vector, force, lever, rolling torque, overlap ratio, losses, sliding), both
// displacement forms, with and without rolling resistance, for the paper's law, van Wachem's
// soft one, the corner cases (no tangential spring, no friction, no dashpots) and Hertz-Mindlin
// (van Wachem's material as Lethe gives it; elastic and frictionless; stiff glass).
TEST(PairKernel, EveryBuildGivesTheScalar3dContactLawToTheBit) {
  const DepthPairs s = random_depth_pairs(4099, 4);
  // First which pairs touch (slots from 5 on), as the scalar pass decided with dot(p, p).
  const auto slots = static_cast<std::int64_t>(s.li.size());
  const auto pk = s.particles();
  expect_codes_of_every_build(
      5, slots,
      [&](SimdBuild b, std::uint8_t* code) {
        fluidbed::classify_pairs_depth_on(b, pk, s.li.data(), s.lj.data(), 5, slots, code);
      },
      [&](std::uint8_t* code) {
        fluidbed::classify_pairs_depth(pk, s.li.data(), s.lj.data(), 5, slots, code);
      },
      [&](std::int64_t k) {
        const std::int32_t i = s.li[k], j = s.lj[k];
        const fluidbed::Vec3 d{s.x[j] - s.x[i], s.y[j] - s.y[i], s.z[j] - s.z[i]};
        const double L2 = fluidbed::dot(d, d), R = s.r[i] + s.r[j];
        return L2 <= 0.0 ? 2 : (L2 < R * R ? 1 : 0);
      });
  std::vector<ContactParams> laws = {
      {50000.0, 50000.0, 0.15, 0.15, 0.3, 0.0},      // the paper's
      {624.0, 624.0, 0.00176, 0.00176, 0.3, 0.025},  // van Wachem's, rolling resistance
      {50000.0, 0.0, 0.15, 0.15, 0.3, 0.1},          // no tangential spring
      {50000.0, 50000.0, 0.15, 0.15, 0.0, 0.0},      // frictionless
      {50000.0, 14285.7, 0.0, 0.0, 0.3, 0.4},        // undamped, strong rolling resistance
      {1.0e6, 8.0e5, 2.5, 1.1, 0.45, 0.0},           // stiff
  };
  for (const auto& [E, nu, e, mu, mu_r] : {std::array<double, 5>{1.0e7, 0.3, 0.9, 0.3, 0.025},
                                           std::array<double, 5>{1.0e7, 0.3, 1.0, 0.0, 0.0},
                                           std::array<double, 5>{6.3e10, 0.23, 0.5, 0.45, 0.0}}) {
    ContactParams h{0.0, 0.0, 0.0, 0.0, mu, mu_r};
    fluidbed::set_hertz(h, E, nu, e);
    laws.push_back(h);
  }
  const auto count = static_cast<std::int64_t>(s.on.size());
  const auto n = static_cast<std::size_t>(count);
  const char* names[16] = {"dn",     "ds",      "ds_y",    "ds_z",    "fx",     "fy",
                           "fz",     "lever_x", "lever_y", "lever_z", "roll_x", "roll_y",
                           "roll_z", "ratio",   "dashpot", "friction"};
  int sliding = 0, sticking = 0, fresh = 0, apart = 0, rolling = 0, turned = 0, hertz = 0;
  const int builds = for_every_build_law_and_form(
      laws.size(), [&](SimdBuild b, std::size_t law, bool incremental, double dtau) {
        std::vector<double> hdn = s.dn, hds = s.ds, hdy = s.ds_y, hdz = s.ds_z;
        for (std::int32_t slot : s.on)
          if (slot < 0) {
            const auto k = static_cast<std::size_t>(~slot);
            hdn[k] = hds[k] = hdy[k] = hdz[k] = 0.0;
          }
        DepthOutputs got(n);
        fluidbed::depth_contacts_on(
            b,
            {s.particles(), s.li.data(), s.lj.data(), hdn.data(), hds.data(), s.on.data(), count,
             laws[law], incremental, dtau, hdy.data(), hdz.data()},
            got.out());
        for (std::size_t q = 0; q < n; ++q) {
          const DepthContact want = scalar_depth_contact(s, s.on[q], laws[law], incremental, dtau);
          for (int field = 0; field < 16; ++field)
            ASSERT_EQ(bits_of(got.f(field)[q]), bits_of(want.v[static_cast<std::size_t>(field)]))
                << names[field] << ", contact " << q;
          ASSERT_EQ(got.sliding[q], want.sliding) << "contact " << q;
          sliding += want.sliding;
          sticking += 1 - want.sliding;
          fresh += s.on[q] < 0;
          apart += want.v[13] <= 0.0;
          rolling += want.v[10] != 0.0;
          turned += s.on[q] >= 0 && s.ds[static_cast<std::size_t>(s.on[q])] != 0.0;
          hertz += laws[law].hertz && want.v[4] != 0.0;
        }
      });
  EXPECT_GE(builds, 1);
  EXPECT_GT(sliding, 1000);
  EXPECT_GT(sticking, 1000);
  EXPECT_GT(fresh, 1000);
  EXPECT_GT(apart, 100);
  EXPECT_GT(rolling, 1000);
  EXPECT_GT(turned, 1000);
  EXPECT_GT(hertz, 1000);

  // The build the loader chose gives the baseline's bits.
  for (const bool incremental : {true, false}) {
    DepthOutputs a(n), c(n);
    const fluidbed::DepthContactIn in{s.particles(), s.li.data(), s.lj.data(),   s.dn.data(),
                                      s.ds.data(),   s.on.data(), count,         laws[1],
                                      incremental,   2e-5,        s.ds_y.data(), s.ds_z.data()};
    fluidbed::depth_contacts(in, a.out());
    fluidbed::depth_contacts_on(SimdBuild::baseline, in, c.out());
    for (std::size_t k = 0; k < a.v.size(); ++k)
      ASSERT_EQ(bits_of(a.v[k]), bits_of(c.v[k])) << "value " << k;
    EXPECT_EQ(a.sliding, c.sliding);
  }
}

namespace {

// Random contacts of spheres with the six walls of a thick slab (dem/walls.hpp: bottom, left,
// right, front, back, lid), as the particle pass lists them: sphere q against wall q % 6, its
// centre 0.2 to 1 radius from the wall (a few at the radius to rounding's side inside), random
// velocities and spins, and the wall history of entry s = q * 6 + c as random_depth_pairs draws a
// pair's (random, zero, or along the normal).
struct WallContacts {
  DepthPairs spheres;  // li, lj, dn and the shear unused: the history is by entry
  std::vector<double> nx, ny, nz, offset;
  std::vector<double> dn, ds, ds_y, ds_z;  // by entry
  std::vector<std::int32_t> on, particle;
  static constexpr std::int32_t kWalls = 6;
};

WallContacts random_wall_contacts(std::size_t n, std::uint64_t seed) {
  const double W = 0.09, H = 0.5, T = 0.008;
  WallContacts s;
  s.nx = {0.0, 1.0, -1.0, 0.0, 0.0, 0.0};
  s.ny = {1.0, 0.0, 0.0, 0.0, 0.0, -1.0};
  s.nz = {0.0, 0.0, 0.0, 1.0, -1.0, 0.0};
  s.offset = {0.0, 0.0, -W, 0.0, -T, -H};
  // The spheres' radii, velocities, spins and masses from random_depth_pairs' first particles.
  s.spheres = random_depth_pairs(n, seed);
  DepthPairs& p = s.spheres;
  std::mt19937_64 rng(seed + 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::size_t entries = 2 * n * static_cast<std::size_t>(WallContacts::kWalls);
  s.dn.assign(entries, 0.0);
  s.ds.assign(entries, 0.0);
  s.ds_y.assign(entries, 0.0);
  s.ds_z.assign(entries, 0.0);
  for (std::size_t q = 0; q < n; ++q) {
    const std::size_t i = 2 * q, c = q % WallContacts::kWalls;
    const double r = p.r[i];
    const double d = q % 97 == 5 ? std::nextafter(r, 0.0) : r * (0.2 + 0.8 * u(rng));
    p.x[i] = 0.3 * W + 0.4 * W * u(rng);
    p.y[i] = 0.3 * H + 0.4 * H * u(rng);
    p.z[i] = 0.5 * T;
    double* along[6] = {&p.y[i], &p.x[i], &p.x[i], &p.z[i], &p.z[i], &p.y[i]};
    *along[c] = c == 2 ? W - d : c == 4 ? T - d : c == 5 ? H - d : d;
    const std::size_t e = i * static_cast<std::size_t>(WallContacts::kWalls) + c;
    const int kind = static_cast<int>(q % 11);
    const double a = 2e-4 * u(rng) - 1e-4;
    s.dn[e] = 1.2e-4 * u(rng) - 2e-5;
    if (kind == 1) {  // along the normal: nothing in the plane
      s.ds[e] = a * s.nx[c];
      s.ds_y[e] = a * s.ny[c];
      s.ds_z[e] = a * s.nz[c];
    } else if (kind != 0) {
      s.ds[e] = a;
      s.ds_y[e] = 2e-4 * u(rng) - 1e-4;
      s.ds_z[e] = 2e-4 * u(rng) - 1e-4;
    }
    const auto entry = static_cast<std::int32_t>(e);
    const bool fresh = u(rng) < 0.3;
    if (fresh) s.dn[e] = s.ds[e] = s.ds_y[e] = s.ds_z[e] = 0.0;  // as the pass clears it
    s.on.push_back(fresh ? ~entry : entry);
    s.particle.push_back(static_cast<std::int32_t>(i));
  }
  return s;
}

// Contact q as DemSolver::particle_pass_depth computed it before the kernel: the contact point's
// velocity, time_since_touch_wall for a new contact, hertz_params with R_i and m_i,
// contact_force_3d, rolling_torque_3d against the sphere's spin and its loss.
DepthContact scalar_wall_contact(const WallContacts& s, std::size_t q, const ContactParams& p,
                                 bool incremental, double dtau) {
  using fluidbed::Vec3;
  const DepthPairs& P = s.spheres;
  const bool fresh = s.on[q] < 0;
  const auto e = static_cast<std::size_t>(fresh ? ~s.on[q] : s.on[q]);
  const auto i = static_cast<std::size_t>(s.particle[q]);
  const std::size_t c = e - i * static_cast<std::size_t>(WallContacts::kWalls);
  const double d = s.nx[c] * P.x[i] + s.ny[c] * P.y[i] + s.nz[c] * P.z[i] - s.offset[c];
  const Vec3 n{-s.nx[c], -s.ny[c], -s.nz[c]};
  const double overlap = P.r[i] - d;
  const Vec3 spin{P.wx[i], P.wy[i], P.wz[i]};
  const Vec3 vr = Vec3{P.vx[i], P.vy[i], P.vz[i]} + P.r[i] * fluidbed::cross(spin, n);
  const double vn = fluidbed::dot(vr, n);
  double tau = dtau;
  if (fresh && incremental) tau = std::min(fluidbed::time_since_touch_wall(overlap, vn), dtau);
  const double dn = incremental ? s.dn[e] + vn * tau : overlap;
  const ContactParams law = p.hertz ? fluidbed::hertz_params(p, dn, P.r[i], P.mass[i]) : p;
  Vec3 shear{s.ds[e], s.ds_y[e], s.ds_z[e]};
  fluidbed::ContactForce3 f = fluidbed::contact_force_3d(law, dn, shear, n, vr, tau, dtau);
  Vec3 roll;
  if (p.mu_r > 0.0) {
    roll = fluidbed::rolling_torque_3d(p.mu_r, P.r[i], f.fn_spring, spin, P.inv_i[i], dtau);
    f.loss.friction += std::sqrt(fluidbed::dot(roll, roll) * fluidbed::dot(spin, spin)) * dtau;
  }
  return {{dn, shear.x, shear.y, shear.z, f.force.x, f.force.y, f.force.z, f.lever.x, f.lever.y,
           f.lever.z, roll.x, roll.y, roll.z, overlap / P.r[i], f.loss.dashpot, f.loss.friction},
          f.sliding ? 1 : 0};
}

}  // namespace

// The walls' kernel against the scalar law to the bit, every wall, both displacement forms,
// with and without rolling resistance, linear and Hertz-Mindlin laws (each of the eight forms of
// its loop), every build.
TEST(PairKernel, EveryBuildGivesTheScalarWallContactLawToTheBit) {
  const WallContacts s = random_wall_contacts(4099, 9);
  const std::vector<ContactParams> laws = [] {
    std::vector<ContactParams> l = {
        {50000.0, 50000.0, 0.15, 0.15, 0.3, 0.0},      // the paper's
        {624.0, 624.0, 0.00176, 0.00176, 0.3, 0.025},  // van Wachem's, rolling resistance
        {50000.0, 0.0, 0.15, 0.15, 0.3, 0.1},          // no tangential spring
        {50000.0, 50000.0, 0.15, 0.15, 0.0, 0.0},      // frictionless
    };
    // Hertz-Mindlin: van Wachem's material as Lethe gives it, with rolling resistance; stiff
    // glass without.
    ContactParams h{0.0, 0.0, 0.0, 0.0, 0.3, 0.025};
    fluidbed::set_hertz(h, 1.0e7, 0.3, 0.9);
    l.push_back(h);
    ContactParams glass{0.0, 0.0, 0.0, 0.0, 0.45, 0.0};
    fluidbed::set_hertz(glass, 6.3e10, 0.23, 0.5);
    l.push_back(glass);
    return l;
  }();
  const auto count = static_cast<std::int64_t>(s.on.size());
  const auto n = static_cast<std::size_t>(count);
  int sliding = 0, sticking = 0, fresh = 0, rolling = 0, turned = 0, hertz = 0;
  std::array<int, WallContacts::kWalls> per_wall{};
  auto input = [&](const ContactParams& law, bool incremental, double dtau) {
    return fluidbed::WallContactIn{
        s.spheres.particles(), s.on.data(), s.particle.data(), count,
        WallContacts::kWalls,  s.nx.data(), s.ny.data(),       s.nz.data(),
        s.offset.data(),       s.dn.data(), s.ds.data(),       s.ds_y.data(),
        s.ds_z.data(),         law,         incremental,       dtau};
  };
  const int builds = for_every_build_law_and_form(
      laws.size(), [&](SimdBuild b, std::size_t law, bool incremental, double dtau) {
        DepthOutputs got(n);
        fluidbed::wall_contacts_depth_on(b, input(laws[law], incremental, dtau), got.out());
        for (std::size_t q = 0; q < n; ++q) {
          const DepthContact want = scalar_wall_contact(s, q, laws[law], incremental, dtau);
          for (int field = 0; field < 16; ++field)
            ASSERT_EQ(bits_of(got.f(field)[q]), bits_of(want.v[static_cast<std::size_t>(field)]))
                << "field " << field << ", contact " << q;
          ASSERT_EQ(got.sliding[q], want.sliding) << "contact " << q;
          sliding += want.sliding;
          sticking += 1 - want.sliding;
          fresh += s.on[q] < 0;
          rolling += want.v[10] != 0.0;
          turned += s.on[q] >= 0 && s.ds[static_cast<std::size_t>(s.on[q])] != 0.0;
          hertz += laws[law].hertz && want.v[4] != 0.0;
          ++per_wall[q % WallContacts::kWalls];
        }
      });
  EXPECT_GE(builds, 1);
  EXPECT_GT(sliding, 1000);
  EXPECT_GT(sticking, 1000);
  EXPECT_GT(fresh, 1000);
  EXPECT_GT(rolling, 1000);
  EXPECT_GT(turned, 1000);
  EXPECT_GT(hertz, 1000);
  for (const int k : per_wall) EXPECT_GT(k, 1000);

  // The build the loader chose gives the baseline's bits.
  for (const bool incremental : {true, false}) {
    DepthOutputs a(n), c(n);
    fluidbed::wall_contacts_depth(input(laws[1], incremental, 2e-5), a.out());
    fluidbed::wall_contacts_depth_on(SimdBuild::baseline, input(laws[1], incremental, 2e-5),
                                     c.out());
    for (std::size_t k = 0; k < a.v.size(); ++k)
      ASSERT_EQ(bits_of(a.v[k]), bits_of(c.v[k])) << "value " << k;
    EXPECT_EQ(a.sliding, c.sliding);
  }
}
