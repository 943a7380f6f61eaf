// Scene files: defaults, overrides, unknown keys, types and physics checks, each error naming
// its key.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "run/packed_bed.hpp"
#include "scene/lattice.hpp"
#include "scene/scene_loader.hpp"

using namespace fluidbed;

TEST(Scene, DefaultsAreThePapers) {
  const Settings s = parse_scene("", "empty.toml");
  EXPECT_EQ(s.particles.count, 2400);
  EXPECT_DOUBLE_EQ(s.particles.diameter, 0.004);
  EXPECT_DOUBLE_EQ(s.particles.density, 2700.0);
  EXPECT_DOUBLE_EQ(s.contact.stiffness, 50000.0);
  EXPECT_DOUBLE_EQ(s.contact.friction, 0.3);
  EXPECT_DOUBLE_EQ(s.contact.damping, 0.15);
  EXPECT_DOUBLE_EQ(s.time.dt, 1.5e-5);
  EXPECT_DOUBLE_EQ(s.domain.width, 0.15);
  EXPECT_DOUBLE_EQ(s.domain.height, 0.9);
  EXPECT_DOUBLE_EQ(s.domain.thickness, 0.004);
  EXPECT_EQ(s.time.integrator, Integrator::Newmark);
  EXPECT_EQ(s.contact.displacement, Displacement::Incremental);
}

TEST(Scene, ReadsValuesAndOverrides) {
  const Settings s = parse_scene("[particles]\ndensity = 1350\n[time]\ndt = 3e-5\n", "t.toml",
                                 {"contact.damping=0", "time.integrator=velocity_verlet",
                                  "particles.density=1000.5", "domain.top_wall=true"});
  EXPECT_DOUBLE_EQ(s.particles.density, 1000.5);  // the override wins over the file
  EXPECT_DOUBLE_EQ(s.time.dt, 3e-5);
  EXPECT_DOUBLE_EQ(s.contact.damping, 0.0);
  EXPECT_EQ(s.time.integrator, Integrator::VelocityVerlet);
  EXPECT_TRUE(s.domain.top_wall);
}

TEST(Scene, RefusesUnknownKeysAndSections) {
  EXPECT_NE(
      fluidbed::testing::scene_error("[particles]\ndiametre = 0.004\n").find("particles.diametre"),
      std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[partcles]\ncount = 3\n").find("[partcles]"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("", {"contact.stifness=3"}).find("contact.stifness"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("", {"nonsense"}).find("section.key=value"),
            std::string::npos);
}

TEST(Scene, RefusesWrongTypes) {
  EXPECT_NE(
      fluidbed::testing::scene_error("[particles]\ncount = \"many\"\n").find("particles.count"),
      std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[particles]\ncount = 2.5\n").find("particles.count"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[time]\ndt = true\n").find("time.dt"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[time\n").find("t.toml:1"),
            std::string::npos);  // syntax: line named
}

TEST(Scene, RefusesImpossibleValues) {
  EXPECT_NE(
      fluidbed::testing::scene_error("[particles]\ndiameter = -0.004\n").find("particles.diameter"),
      std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[particles]\ndensity = 0\n").find("particles.density"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[time]\ndt = 0\n").find("time.dt"), std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[contact]\nfriction = -1\n").find("contact.friction"),
            std::string::npos);
  EXPECT_NE(
      fluidbed::testing::scene_error("[time]\nintegrator = \"rk4\"\n").find("time.integrator"),
      std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("[inlet]\nkind = \"nozzle\"\n").find("inlet.kind"),
            std::string::npos);
  EXPECT_NE(
      fluidbed::testing::scene_error("[domain]\nthickness = 0.003\n").find("domain.thickness"),
      std::string::npos);
  // 10,000 spheres of 4 mm cannot fit in 0.15 m x 0.9 m (8,325 lattice cells).
  const std::string many = fluidbed::testing::scene_error("[particles]\ncount = 10000\n");
  EXPECT_NE(many.find("particles.count"), std::string::npos);
  EXPECT_NE(many.find("fit"), std::string::npos);
  EXPECT_NE(
      fluidbed::testing::scene_error("[particles]\nplacement = \"single\"\ncount = 1\nx = 0.001\n")
          .find("particles.x"),
      std::string::npos);
}

// A size that would exhaust the machine is refused before anything is allocated, naming the key
// that makes it large, and quickly; a domain only tall is not (it costs nothing until filled).
TEST(Scene, RefusesSizesThatWouldExhaustTheMemory) {
  EXPECT_NE(
      fluidbed::testing::scene_error("", {"particles.count=2000000000"}).find("particles.count"),
      std::string::npos);
  const std::string gas =
      fluidbed::testing::scene_error("", {"gas.cells_x=100000", "gas.cells_y=100000",
                                          "particles.diameter=1e-6", "particles.count=10"});
  EXPECT_NE(gas.find("gas.cells_x times gas.cells_y"), std::string::npos) << gas;
  EXPECT_NE(gas.find("GB of memory"), std::string::npos) << gas;
  // Rows and columns are counted in integers: 10^300 m is refused, 100 km is not.
  EXPECT_NE(fluidbed::testing::scene_error("", {"domain.height=1e300"})
                .find("10^8 particles.diameter high"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("", {"domain.width=1e300"})
                .find("10^8 particles.diameter wide"),
            std::string::npos);
  EXPECT_EQ(fluidbed::testing::scene_error("", {"domain.height=100000"}), "");
}

// The lattice's shape gives the same sites, in the same order, as listing them one by one.
TEST(Scene, LatticeShapeNumbersTheSitesAsTheListDoes) {
  for (const auto& [w, top, d] : {std::array<double, 3>{0.15, 0.9, 0.004},
                                  std::array<double, 3>{0.15, 0.3, 0.004},
                                  std::array<double, 3>{0.006, 0.05, 0.004},
                                  std::array<double, 3>{0.0042, 0.0041, 0.004},
                                  std::array<double, 3>{0.1003, 0.2, 0.0035},
                                  std::array<double, 3>{0.002, 0.9, 0.004}}) {
    const auto sites = lattice_sites(w, top, d);
    const LatticeShape shape(w, top, d);
    ASSERT_EQ(shape.size(), sites.size()) << w << " x " << top << ", d " << d;
    for (std::size_t k = 0; k < sites.size(); ++k) {
      EXPECT_EQ(shape.site(k).x, sites[k].x) << k;
      EXPECT_EQ(shape.site(k).y, sites[k].y) << k;
    }
  }
}

TEST(Scene, ResolvedSceneReadsBackIdentically) {
  const Settings s = parse_scene("[particles]\ncount = 100\nseed = 42\n", "t.toml",
                                 {"scene.name=roundtrip", "contact.stiffness=800"});
  const std::string text = to_toml(s);
  const Settings back = parse_scene(text, "resolved.toml");
  EXPECT_EQ(to_toml(back), text);
  EXPECT_EQ(back.particles.seed, 42u);
  EXPECT_DOUBLE_EQ(back.contact.stiffness, 800.0);
}

TEST(Scene, ShippedScenesAreValid) {
  int found = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::string(FLUIDBED_ASSET_DIR) + "/scenes")) {
    if (e.path().extension() != ".toml") continue;
    ++found;
    EXPECT_NO_THROW(load_scene(e.path().string())) << e.path();
  }
  EXPECT_GE(found, 2);
}

TEST(Scene, MissingFileNamesThePath) {
  try {
    load_scene("/nonexistent/scene.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.toml"), std::string::npos);
  }
}

TEST(Scene, KeysThatFollowAnotherAreLeftOutUntilSet) {
  // Unset, contact.wall_friction follows contact.friction and is not in the resolved scene (whose
  // text keys the packed-bed cache, so a scene without it resolves as before the key existed).
  const Settings plain = parse_scene("", "t.toml");
  EXPECT_FALSE(plain.contact.wall_friction);
  EXPECT_EQ(to_toml(plain).find("wall_friction"), std::string::npos);
  const Settings set = parse_scene("[contact]\nwall_friction = 0.1\n", "t.toml",
                                   {"particles.packing_rolling_friction=0.2"});
  ASSERT_TRUE(set.contact.wall_friction);
  EXPECT_DOUBLE_EQ(*set.contact.wall_friction, 0.1);
  const std::string text = to_toml(set);
  EXPECT_NE(text.find("wall_friction = 0.1"), std::string::npos) << text;
  EXPECT_EQ(to_toml(parse_scene(text, "resolved.toml")), text);
  EXPECT_NE(fluidbed::testing::scene_error("", {"contact.wall_friction=-0.1"})
                .find("contact.wall_friction"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("", {"contact.wall_friction=true"}).find("a number"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error(
                "[particles]\nplacement = 'packed'\npacking_scene = 'other.toml'\n",
                {"particles.packing_rolling_friction=0.2"})
                .find("particles.packing_rolling_friction"),
            std::string::npos);
}

TEST(Scene, SmoothedVoidFractionNeedsItsLengthAndOnlyIt) {
  const Settings plain = parse_scene("", "test.toml");
  EXPECT_EQ(plain.coupling.void_fraction, VoidFraction::Exact);
  const Settings smoothed = parse_scene(
      "", "test.toml", {"coupling.void_fraction=\"smoothed\"", "coupling.void_fraction_length=0.0015"});
  EXPECT_EQ(smoothed.coupling.void_fraction, VoidFraction::Smoothed);
  EXPECT_DOUBLE_EQ(smoothed.coupling.void_fraction_length, 0.0015);
  EXPECT_NE(fluidbed::testing::scene_error("", {"coupling.void_fraction=\"smoothed\""})
                .find("coupling.void_fraction_length"),
            std::string::npos);
  EXPECT_NE(
      fluidbed::testing::scene_error("", {"coupling.void_fraction_length=0.002"}).find("\"exact\""),
      std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error("", {"coupling.void_fraction=\"blurred\""})
                .find("exact, smoothed"),
            std::string::npos);
  EXPECT_NE(fluidbed::testing::scene_error(
                "", {"coupling.void_fraction=\"smoothed\"", "coupling.void_fraction_length=-1"})
                .find("coupling.void_fraction_length"),
            std::string::npos);
}

TEST(Scene, PackingFrictionIsThePackingsOwn) {
  // Lethe's loading: packed with rolling friction 0.2, fluidized with 0.025.
  const Settings bed = parse_scene("[particles]\nplacement = 'packed'\n", "t.toml",
                                   {"contact.rolling_friction=0.025",
                                    "particles.packing_rolling_friction=0.2",
                                    "particles.packing_friction=0.5"});
  const Settings packing = packing_settings_for(bed);
  EXPECT_DOUBLE_EQ(packing.contact.rolling_friction, 0.2);
  EXPECT_DOUBLE_EQ(packing.contact.friction, 0.5);
  EXPECT_FALSE(packing.particles.packing_rolling_friction);  // consumed: the packing's own values
  EXPECT_DOUBLE_EQ(bed.contact.rolling_friction, 0.025);
  // Unset: the packing takes the bed's contact values.
  const Settings same = packing_settings_for(parse_scene("", "t.toml"));
  EXPECT_DOUBLE_EQ(same.contact.rolling_friction, Settings{}.contact.rolling_friction);
  EXPECT_DOUBLE_EQ(same.contact.friction, Settings{}.contact.friction);
}
