// `fluidbed bench --peer liggghts`: bad input is refused in one line before anything runs, and,
// where Debian's LIGGGHTS is installed, a small packing runs in both codes and bench.json's
// "peer" object holds the same work on both sides and speeds that follow from its own times.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../test_support.hpp"

using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

bool liggghts_installed() {
  if (const char* e = std::getenv("FLUIDBED_LIGGGHTS"); e && *e) return fs::exists(e);
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin");
  for (std::string d; std::getline(dirs, d, ':');)
    if (!d.empty() && fs::exists(fs::path(d) / "liggghts")) return true;
  return false;
}

long lines(const std::string& s) {
  return std::count(s.begin(), s.end(), '\n');
}

}  // namespace

TEST(BenchPeer, RefusesAnUnknownPeerAndAPackedStart) {
  const fs::path dir = temp_dir("bench-peer-refused");
  const CommandResult unknown =
      run_fluidbed("bench --peer lammps --out " + (dir / "a").string(), "peer-unknown");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("known: liggghts"), std::string::npos) << unknown.err;
  EXPECT_EQ(lines(unknown.err), 1) << unknown.err;
  const CommandResult packed =
      run_fluidbed("bench " + std::string(FLUIDBED_ASSET_DIR) +
                       "/scenes/xu_yu_1997.toml --peer liggghts --out " + (dir / "b").string(),
                   "peer-packed");
  EXPECT_EQ(packed.status, 2);
  EXPECT_NE(packed.err.find("\"packed\""), std::string::npos) << packed.err;
  EXPECT_EQ(lines(packed.err), 1) << packed.err;
  EXPECT_FALSE(fs::exists(dir / "a"));
  EXPECT_FALSE(fs::exists(dir / "b"));
}

// 300 spheres of packing.toml, 3000 steps (0.045 s), in fluidbed and in LIGGGHTS.
TEST(BenchPeer, SmallPackingAgainstLiggghts) {
  if (!liggghts_installed())
    GTEST_SKIP() << "LIGGGHTS is not installed (apt-get install liggghts), or set "
                    "FLUIDBED_LIGGGHTS to its binary";
  const fs::path dir = temp_dir("bench-peer-run");
  const CommandResult r = run_fluidbed(
      "bench --peer liggghts --set particles.count=300 --until 0.045 --out " + dir.string(),
      "peer-run");
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("same work in both: 300 particles, 3000 steps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ratio fluidbed / LIGGGHTS"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "liggghts" / "in.liggghts"));
  EXPECT_TRUE(fs::exists(dir / "liggghts" / "log.liggghts"));

  const auto bench = nlohmann::json::parse(read_file(dir / "bench.json"));
  ASSERT_TRUE(bench.contains("peer")) << bench.dump(2);
  const auto& peer = bench["peer"];
  EXPECT_EQ(peer["code"], "liggghts");
  EXPECT_NE(peer["version"].get<std::string>().find("3.8"), std::string::npos);
  EXPECT_EQ(peer["processes"], 1);
  EXPECT_EQ(peer["same_work"], true);
  const auto& work = peer["work"];
  EXPECT_EQ(work["particles"], 300);
  EXPECT_EQ(work["steps"], 3000);
  EXPECT_EQ(work["dt_s"], 1.5e-5);
  EXPECT_NEAR(work["end_time_s"].get<double>(), 0.045, 1e-12);
  // Both sides did that work, and the top level (fluidbed's bench) agrees.
  for (const char* side : {"fluidbed", "liggghts"}) {
    const auto& c = peer[side];
    for (const char* key : {"particles", "steps", "dt_s"})
      EXPECT_EQ(c[key], work[key]) << side << key;
    EXPECT_NEAR(c["end_time_s"].get<double>(), 0.045, 1e-12) << side;
    const double loop = c["loop_wall_s"].get<double>();
    EXPECT_GT(loop, 0.0) << side;
    EXPECT_NEAR(c["particle_steps_per_s"].get<double>(), 300.0 * 3000.0 / loop,
                1e-9 * 300.0 * 3000.0 / loop)
        << side;
    EXPECT_GE(c["setup_s"].get<double>(), 0.0) << side;
  }
  EXPECT_EQ(bench["particles"], 300);
  EXPECT_EQ(bench["steps"], 3000);
  EXPECT_EQ(peer["fluidbed"]["loop_wall_s"], bench["wall_time_s"]);
  const auto& l = peer["liggghts"];
  EXPECT_NEAR(l["setup_s"].get<double>(),
              l["process_wall_s"].get<double>() - l["loop_wall_s"].get<double>(), 1e-12);
  EXPECT_GT(l["process_wall_s"].get<double>(), l["loop_wall_s"].get<double>());
  const double ratio = peer["fluidbed"]["particle_steps_per_s"].get<double>() /
                       l["particle_steps_per_s"].get<double>();
  EXPECT_NEAR(peer["ratio"].get<double>(), ratio, 1e-12 * ratio);
  EXPECT_GT(ratio, 0.0);
  // The deck left out the gas, and so did fluidbed: its scene reports no gas time.
  EXPECT_EQ(bench["split"]["gas"]["seconds"], 0.0);
}
