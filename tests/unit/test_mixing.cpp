// Lacey's mixing index (model.md 6) on synthetic sets: segregated, layered by initial height,
// and random.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/mixing.hpp"
#include "core/errors.hpp"
#include "core/random.hpp"
#include "synthetic_bed.hpp"

using fluidbed::kinds_by_initial_height;
using fluidbed::lacey_index;
using fluidbed::LaceyResult;
using fluidbed::LaceySettings;

namespace {

constexpr double kBedWidth = 0.15, kBedHeight = 0.9;  // m, the paper's domain

}  // namespace

TEST(Mixing, KindsByInitialHeightAreTheLowerAndUpperHalves) {
  const std::vector<double> y = {0.3, 0.1, 0.2, 0.1, 0.5, 0.4};
  const std::vector<std::uint8_t> k = kinds_by_initial_height(y);
  EXPECT_EQ(k, (std::vector<std::uint8_t>{1, 0, 0, 0, 1, 1}));
  // An odd count: the middle particle is of the upper kind.
  EXPECT_EQ(kinds_by_initial_height({0.2, 0.1, 0.3}), (std::vector<std::uint8_t>{1, 0, 1}));
}

TEST(Mixing, FullySegregatedSetIsZero) {
  // The hexagonal bed, kind 1 above y = 0.1 m: a line between rows of sample cells (0.02 m), so
  // that every counted cell holds one kind. s^2 = p (1 - p) = s0^2 exactly: M = 0.
  const auto p = fluidbed::testing::hex_bed(kBedWidth, 0.2);
  std::vector<std::uint8_t> kind(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) kind[i] = p.y[i] > 0.1 ? 1 : 0;
  const LaceyResult r = lacey_index(p, kind, kBedWidth, kBedHeight);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.index, 0.0, 1e-12);
  EXPECT_NEAR(r.s2, r.s0_2, 1e-15);
  EXPECT_GT(r.cells, 60);
  // Sample cells 18.75 x 20 mm of a packed layer: about 27 spheres (less at the surface).
  EXPECT_NEAR(r.mean_per_cell, 26.0, 2.0);
  // Halves by initial height of a bed 0.17 m deep: the interface (the median height, 0.085 m)
  // runs through the row of cells 0.08-0.10 m, a quarter of it below: that row, one of nine,
  // holds a kind-1 fraction x = 3/4, so s0^2 - s^2 = (1/9) (1/4 - 1/16) = 0.021 and
  // M = 0.021 / (1/4 - 1/(4 n)) = 0.087 with n = 25 spheres per cell.
  const auto q = fluidbed::testing::hex_bed(kBedWidth, 0.17);
  const LaceyResult h = lacey_index(q, kinds_by_initial_height(q.y), kBedWidth, kBedHeight);
  ASSERT_TRUE(h.ok);
  EXPECT_NEAR(h.p, 0.5, 0.001);
  EXPECT_NEAR(h.index, 0.087, 0.01);
}

TEST(Mixing, RandomSetIsAboutOne) {
  // Kinds drawn at random (p = 1/2) over the packed bed. s^2 then scatters about sr^2 with a
  // relative spread of sqrt(2 / K) over K cells, so M = 1 +- sqrt(2 / K) / (n - 1): with K = 80
  // cells of n = 26 spheres, 0.006. Tolerance 0.05 for each of ten seeds (8 of those standard
  // deviations), 0.02 for their mean.
  const auto p = fluidbed::testing::hex_bed(kBedWidth, 0.2);
  double sum = 0.0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    fluidbed::SplitMix64 rng(seed);
    std::vector<std::uint8_t> kind(p.size());
    for (auto& k : kind) k = rng.uniform() < 0.5 ? 1 : 0;
    const LaceyResult r = lacey_index(p, kind, kBedWidth, kBedHeight);
    ASSERT_TRUE(r.ok);
    EXPECT_NEAR(r.index, 1.0, 0.05) << "seed " << seed;
    sum += r.index;
  }
  EXPECT_NEAR(sum / 10.0, 1.0, 0.02);
}

TEST(Mixing, UndefinedCasesAndBadSettings) {
  const auto p = fluidbed::testing::hex_bed(kBedWidth, 0.2);
  // One kind only: M undefined.
  EXPECT_FALSE(lacey_index(p, std::vector<std::uint8_t>(p.size(), 1), kBedWidth, kBedHeight).ok);
  // Cells that must hold more spheres than any does: none counted.
  LaceySettings big;
  big.min_particles = 1000;
  EXPECT_FALSE(lacey_index(p, kinds_by_initial_height(p.y), kBedWidth, kBedHeight, big).ok);
  const auto expect_key = [&](LaceySettings s, const std::string& key) {
    try {
      lacey_index(p, kinds_by_initial_height(p.y), kBedWidth, kBedHeight, s);
      ADD_FAILURE() << key;
    } catch (const fluidbed::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(key + " ", 0), 0u) << e.what();
    }
  };
  expect_key({0.0, 5}, "mixing.cell_size");
  expect_key({0.5, 5}, "mixing.cell_size");
  expect_key({0.02, 0}, "mixing.min_particles");
  EXPECT_THROW(lacey_index(p, {0, 1}, kBedWidth, kBedHeight), std::invalid_argument);
}
