// The particle solver's branch-free pair kernels (dem/pair_kernel.hpp) against the scalar contact
// law (dem/contact_law.hpp): every build of them (AVX-512, AVX2 and plain x86-64, whichever this
// CPU runs; core/simd.hpp) gives the scalar law's bits on random pairs, touching or not.
#include <gtest/gtest.h>

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

KernelPairs random_pairs(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  KernelPairs s;
  for (std::size_t q = 0; q < n; ++q) {
    const double ri = 0.001 + 0.002 * u(rng), rj = 0.001 + 0.002 * u(rng);
    const double R = ri + rj;
    const double a = 2.0 * std::numbers::pi * u(rng);
    double L = R * (0.2 + 1.1 * u(rng));
    if (q % 97 == 5) L = R;  // at the sum of the radii, to rounding
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

}  // namespace

// Which pairs touch: 1 closer than the sum of the radii, 2 for coincident centres, 0 otherwise
// (at exactly the sum too), from every build; the slots [k0, k1) of a range, not from 0.
TEST(PairKernel, EveryBuildClassifiesPairsAsTheScalarTest) {
  const KernelPairs s = random_pairs(4099, 1);
  const auto n = static_cast<std::int64_t>(s.li.size());
  const std::int64_t k0 = 3;
  int touching = 0, apart = 0, coincident = 0;
  for (SimdBuild b : fluidbed::kSimdBuilds) {
    if (!fluidbed::cpu_runs(b)) continue;
    SCOPED_TRACE(fluidbed::to_string(b));
    std::vector<std::uint8_t> code(static_cast<std::size_t>(n - k0), 255);
    fluidbed::classify_pairs_on(b, s.particles(), s.li.data(), s.lj.data(), k0, n, code.data());
    for (std::int64_t k = k0; k < n; ++k) {
      const std::int32_t i = s.li[k], j = s.lj[k];
      const double px = s.x[j] - s.x[i], py = s.y[j] - s.y[i];
      const double R = s.r[i] + s.r[j];
      const double L2 = px * px + py * py;
      const int want = L2 <= 0.0 ? 2 : (L2 < R * R ? 1 : 0);
      ASSERT_EQ(code[static_cast<std::size_t>(k - k0)], want) << "pair " << k;
      touching += want == 1;
      apart += want == 0;
      coincident += want == 2;
    }
  }
  // The sample has all three kinds.
  EXPECT_GT(touching, 1000);
  EXPECT_GT(apart, 100);
  EXPECT_GT(coincident, 10);
  // The build the loader chose gives the same codes.
  std::vector<std::uint8_t> chosen(static_cast<std::size_t>(n - k0)), baseline(chosen.size());
  fluidbed::classify_pairs(s.particles(), s.li.data(), s.lj.data(), k0, n, chosen.data());
  fluidbed::classify_pairs_on(SimdBuild::baseline, s.particles(), s.li.data(), s.lj.data(), k0, n,
                              baseline.data());
  EXPECT_EQ(chosen, baseline);
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
  int builds = 0, sliding = 0, sticking = 0, fresh = 0, apart = 0;
  for (SimdBuild b : fluidbed::kSimdBuilds) {
    if (!fluidbed::cpu_runs(b)) continue;
    ++builds;
    SCOPED_TRACE(fluidbed::to_string(b));
    for (std::size_t law = 0; law < laws.size(); ++law) {
      for (const bool incremental : {true, false}) {
        SCOPED_TRACE(::testing::Message()
                     << "law " << law << (incremental ? ", incremental" : ", geometric"));
        const double dtau = 1.5e-5 * static_cast<double>(law + 1);
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
        fluidbed::pair_contacts_on(b, s.particles(), s.li.data(), s.lj.data(), hdn.data(),
                                   hds.data(), s.on.data(), count, laws[law], incremental, dtau,
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
      }
    }
  }
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
    fluidbed::pair_contacts(s.particles(), s.li.data(), s.lj.data(), s.dn.data(), s.ds.data(),
                            s.on.data(), count, laws[0], incremental, 1.5e-5, out_in(a, sa));
    fluidbed::pair_contacts_on(SimdBuild::baseline, s.particles(), s.li.data(), s.lj.data(),
                               s.dn.data(), s.ds.data(), s.on.data(), count, laws[0], incremental,
                               1.5e-5, out_in(c, sc));
    for (std::size_t k = 0; k < 8 * n; ++k)
      ASSERT_EQ(bits_of(a[k]), bits_of(c[k])) << "value " << k;
    EXPECT_EQ(sa, sc);
  }
}
