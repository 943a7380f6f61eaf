// A teacher changes the particles of the teaching bed, headlessly (`view --script` without a
// display, as a lesson video is made): the 2,400 spheres become 3 mm ones of the same density, a
// packed bed of them is made (and cached), and the stages take a U_mf for them. That U_mf is the
// scene's measured one scaled by the force balances of the two packed beds; Wen and Yu's
// correlation, an independent law of the same two beds' drag, scales by 0.836 (Re_mf =
// sqrt(33.7^2 + 0.0408 Ar) - 33.7 at 4 and 3 mm): the two agree within 5 % when the packings'
// voidages agree (the correlation holds it fixed). Tens of seconds: label long.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "../test_support.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

namespace {

using namespace fluidbed;
using namespace fluidbed::testing;

TEST(ViewParticles, SmallerSpheresPackAndTheirUmfScalesAsWenAndYus) {
  namespace fs = std::filesystem;
  const fs::path dir = temp_dir("view-particles");
  const fs::path script = dir / "particles.txt";
  {
    std::ofstream out(script);
    out << "at 0.05 particles 0.003 2700\npreset minimum\nat 0.2 quit\n";
  }
  const std::string scene = std::string(FLUIDBED_ASSET_DIR) + "/scenes/teaching.toml";
  const auto r = run_fluidbed("view " + scene + " --script " + script.string() +
                                  " --frame-size 320x200 --out " + (dir / "out").string(),
                              "view-particles");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2400 spheres of 3 mm and 2700 kg/m^3"), std::string::npos) << r.out;
  const std::size_t line = r.out.find(" m/s for the new particles");
  ASSERT_NE(line, std::string::npos) << r.out;
  const std::size_t at = r.out.rfind("U_mf = ", line);
  const double umf = std::stod(r.out.substr(at + 7));
  const std::size_t scaled = r.out.find("scaled by ", at);
  ASSERT_NE(scaled, std::string::npos) << r.out;
  const double ratio = std::stod(r.out.substr(scaled + 10));
  const Settings s = load_scene(scene);
  const auto wen_yu = [&](double d) {
    return wen_yu_umf(d, s.particles.density, s.gas.density, s.gas.viscosity, s.physics.gravity);
  };
  const double expected = wen_yu(0.003) / wen_yu(0.004);
  std::printf("U_mf of 3 mm spheres: %.3f m/s, %.3f of the scene's; Wen and Yu: %.3f\n", umf,
              ratio, expected);
  EXPECT_NEAR(ratio / expected, 1.0, 0.05);
  EXPECT_TRUE(fs::exists(dir / "out" / "frames" / "frame_000006.png"));  // 0.25 s at 25 a second
}

}  // namespace
