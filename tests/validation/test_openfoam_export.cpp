// `fluidbed export --to openfoam`: the DPMFoam case holds the scene's numbers (read back here),
// the contact law's conversion reproduces fluidbed's spring and restitution, bad input is refused
// in one line, and, where OpenFOAM is installed (Debian: apt-get install openfoam), the exported
// cases run in DPMFoam, in parallel (Allrun: decomposePar, mpirun -np 2) and on one process.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <numbers>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "dem/contact_law.hpp"
#include "io/openfoam_export.hpp"
#include "scene/scene_loader.hpp"
#include "sim/placement.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

Settings scene(const std::string& file, const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/" + file, overrides);
}

// The value of `key` in an OpenFOAM dictionary text ("key value;"), first match.
std::string entry(const std::string& text, const std::string& key) {
  const std::regex re("(^|\\n)\\s*" + key + "\\s+([^;\\n]+);");
  std::smatch m;
  if (!std::regex_search(text, m, re)) return "";
  return m[2].str();
}

double number(const std::string& text, const std::string& key) {
  const std::string v = entry(text, key);
  EXPECT_FALSE(v.empty()) << "no entry " << key;
  return v.empty() ? std::nan("") : std::stod(v);
}

struct Point {
  double x, y, z;
};

// A vectorField or lagrangian positions file: "N\n(\n(x y z) [cell]\n...)".
std::vector<Point> read_points(const fs::path& path) {
  std::istringstream in(read_file(path));
  std::vector<Point> pts;
  long n = -1;
  for (std::string line; std::getline(in, line);) {
    if (n < 0) {
      if (std::regex_match(line, std::regex("\\s*[0-9]+\\s*"))) n = std::stol(line);
      continue;
    }
    if (line.empty() || line[0] != '(' || line.size() < 2) continue;
    Point p{};
    if (std::sscanf(line.c_str(), "(%lf %lf %lf)", &p.x, &p.y, &p.z) == 3) pts.push_back(p);
  }
  EXPECT_EQ(static_cast<long>(pts.size()), n) << path;
  return pts;
}

// Debian's openfoam puts DPMFoam in /usr/bin; an upstream install has an etc/bashrc to source.
std::optional<std::string> openfoam_available() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin");
  for (std::string d; std::getline(dirs, d, ':');)
    if (!d.empty() && fs::exists(fs::path(d) / "DPMFoam"))
      return (fs::path(d) / "DPMFoam").string();
  for (const char* root : {"/usr/lib/openfoam", "/opt"}) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(root, ec))
      if (e.path().filename().string().rfind("openfoam", 0) == 0 &&
          fs::exists(e.path() / "etc" / "bashrc"))
        return (e.path() / "etc" / "bashrc").string();
  }
  return std::nullopt;
}

#define REQUIRE_OPENFOAM()                                                              \
  if (!openfoam_available())                                                            \
    GTEST_SKIP() << "OpenFOAM is not installed (Debian: apt-get install openfoam): no " \
                    "DPMFoam on PATH and no /usr/lib/openfoam/openfoam*/etc/bashrc";

// The latest written time folder of a case (not 0).
fs::path last_time(const fs::path& dir) {
  fs::path best;
  double t = 0.0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    char* end = nullptr;
    const double v = std::strtod(name.c_str(), &end);
    if (e.is_directory() && end && *end == '\0' && v > t) {
      t = v;
      best = e.path();
    }
  }
  return best;
}

// "Current number of parcels = N", last in the log.
long last_parcel_count(const std::string& log) {
  const std::regex re("Current number of parcels\\s*=\\s*([0-9]+)");
  long n = -1;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator();
       ++it)
    n = std::stol((*it)[1].str());
  return n;
}

// The uniform value of a patch in a written field: component k of "value uniform (a b c);", or
// the scalar of "value uniform a;" (k = 0).
double patch_value(const std::string& field, const std::string& patch, int k) {
  const auto at = field.find("    " + patch + "\n");
  EXPECT_NE(at, std::string::npos) << patch;
  const std::regex re("value\\s+uniform\\s+\\(?([-0-9.e]+)\\s*([-0-9.e]+)?\\s*([-0-9.e]+)?\\)?;");
  std::smatch m;
  const std::string rest = at == std::string::npos ? "" : field.substr(at);
  if (!std::regex_search(rest, m, re)) {
    ADD_FAILURE() << "no uniform value for " << patch;
    return std::nan("");
  }
  return std::stod(m[1 + k].str());
}

int run_allrun(const fs::path& dir, const std::string& arg) {
  const std::string cmd = "cd '" + dir.string() + "' && ./Allrun " + arg + " > allrun.out 2>&1";
  const int raw = std::system(cmd.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// Runs a written case on 2 MPI processes (Allrun) to `end_time` and returns the parcels' last
// positions, after checking that the run ended cleanly with 300 parcels and was decomposed.
std::vector<Point> run_in_parallel_to_end(const fs::path& dir, double end_time) {
  EXPECT_EQ(run_allrun(dir, ""), 0) << read_file(dir / "allrun.out");
  const std::string log = read_file(dir / "log.DPMFoam");
  EXPECT_NE(log.find("\nEnd"), std::string::npos)
      << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
  EXPECT_EQ(log.find("FOAM FATAL"), std::string::npos);
  EXPECT_EQ(last_parcel_count(log), 300);
  EXPECT_TRUE(fs::exists(dir / "processor1"));
  const fs::path t = last_time(dir);
  if (t.empty()) {
    ADD_FAILURE() << "no time written in " << dir;
    return {};
  }
  EXPECT_NEAR(std::stod(t.filename().string()), end_time, 1e-12);
  return read_points(t / "lagrangian/kinematicCloud/positions");
}

}  // namespace

TEST(OpenfoamExport, CaseHoldsTheScenesNumbers) {
  const Settings s = scene("xu_yu_1997.toml", {"particles.placement=lattice"});
  const fs::path dir = temp_dir("openfoam-bed");
  const OpenfoamCase c = write_openfoam_case(s, dir.string());
  EXPECT_EQ(c.particles, 2400u);
  EXPECT_NE(fs::status(dir / "Allrun").permissions() & fs::perms::owner_exec, fs::perms::none);

  // The mesh: 15 x 45 x 1 cells in three blocks, the slot [0.07, 0.08] m a patch of its own.
  const std::string mesh = read_file(dir / "system/blockMeshDict");
  const std::regex hex("hex \\(([0-9 ]+)\\) \\(([0-9]+) ([0-9]+) ([0-9]+)\\)");
  std::vector<std::array<int, 3>> blocks;
  for (auto it = std::sregex_iterator(mesh.begin(), mesh.end(), hex); it != std::sregex_iterator();
       ++it)
    blocks.push_back({std::stoi((*it)[2]), std::stoi((*it)[3]), std::stoi((*it)[4])});
  const std::vector<std::array<int, 3>> want = {{7, 45, 1}, {1, 45, 1}, {7, 45, 1}};
  EXPECT_EQ(blocks, want);
  // Vertices at x = 0, 0.07, 0.08, 0.15 (y 0 or 0.9, z 0 or 0.004).
  std::vector<double> xs;
  const std::regex vertex("\\n    \\(([-0-9.e]+) ([-0-9.e]+) ([-0-9.e]+)\\)");
  for (auto it = std::sregex_iterator(mesh.begin(), mesh.end(), vertex);
       it != std::sregex_iterator(); ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]), z = std::stod((*it)[3]);
    EXPECT_TRUE(y == 0.0 || y == 0.9) << y;
    EXPECT_TRUE(z == 0.0 || z == 0.004) << z;
    if (xs.empty() || xs.back() != x) xs.push_back(x);
  }
  ASSERT_EQ(xs.size(), 4u);
  const double edges[4] = {0.0, 0.07, 0.08, 0.15};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(xs[k], edges[k], 1e-15) << k;
  EXPECT_NE(mesh.find("type empty;"), std::string::npos);
  for (const char* patch : {"inlet", "bottom", "walls", "outlet", "frontAndBack"})
    EXPECT_NE(mesh.find(std::string("    ") + patch), std::string::npos) << patch;

  // The jet: U W / jet_width = 2.8 x 0.15 / 0.01 = 42 m/s, superficial, at the inlet.
  const std::string u = read_file(dir / "0/U.air");
  EXPECT_NE(u.find("interstitialInletVelocity"), std::string::npos);
  EXPECT_NE(u.find("inletVelocity   uniform (0 42 0)"), std::string::npos);
  const std::string p = read_file(dir / "0/p");
  EXPECT_NE(p.find("fixedFluxPressure"), std::string::npos);

  // Time, air, gravity, decomposition.
  const std::string control = read_file(dir / "system/controlDict");
  EXPECT_EQ(number(control, "deltaT"), 1.5e-5);
  EXPECT_NEAR(number(control, "endTime"), 333333 * 1.5e-5, 1e-12);  // llround(5 s / dt) steps
  const double every = number(control, "writeInterval");
  EXPECT_EQ(std::fmod(333333.0, every), 0.0);  // the last step is a write step
  EXPECT_EQ(entry(control, "application"), "DPMFoam");
  const std::string air = read_file(dir / "constant/transportProperties");
  EXPECT_EQ(number(air, "rho.air"), 1.205);
  EXPECT_DOUBLE_EQ(number(air, "nu"), 1.8e-5 / 1.205);
  EXPECT_NE(read_file(dir / "constant/g").find("value           (0 -9.81 0);"), std::string::npos);
  const std::string dec = read_file(dir / "system/decomposeParDict");
  EXPECT_EQ(number(dec, "numberOfSubdomains"), 2.0);

  // The particles: the scene's lattice start, bit for bit, on the mid-plane.
  const std::vector<Point> pts = read_points(dir / "constant/kinematicCloudPositions");
  const Particles start = place_particles(s);
  ASSERT_EQ(pts.size(), start.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(pts[i].x, start.x[i]) << i;
    ASSERT_EQ(pts[i].y, start.y[i]) << i;
    ASSERT_EQ(pts[i].z, 0.002) << i;
  }

  // The cloud: density, size, the models named, the law's numbers as dpm_collision_law has them.
  const std::string cloud = read_file(dir / "constant/kinematicCloudProperties");
  const DpmCollisionLaw law = dpm_collision_law(s);
  EXPECT_EQ(number(cloud, "rho0"), 2700.0);
  EXPECT_EQ(number(cloud, "youngsModulus"), law.youngs_modulus);
  EXPECT_EQ(number(cloud, "value"), 0.004);
  for (const char* name : {"WenYuDrag", "pairSpringSliderDashpot", "wallSpringSliderDashpot",
                           "manualInjection", "pairCollision"})
    EXPECT_NE(cloud.find(name), std::string::npos) << name;
  EXPECT_NE(cloud.find("b                   1;"), std::string::npos);
  // The header says what differs, with the numbers.
  ASSERT_FALSE(c.notes.empty());
  EXPECT_NE(cloud.find("overlap^(1/4)"), std::string::npos);
  EXPECT_NE(cloud.find("WenYuDrag, the closest"), std::string::npos);
}

// A thick slab (3 spheres deep): each sphere keeps its depth, the front and back are walls for
// the spheres and slip for the gas (still one cell deep), and the notes say so; rolling
// resistance, which DPMFoam lacks, is named in the notes; the Hertz-Mindlin law is refused.
TEST(OpenfoamExport, ThickSlabKeepsEachSpheresDepthBetweenWalls) {
  const Settings s = scene("packing.toml", {"domain.thickness=0.012", "particles.count=300",
                                            "contact.rolling_friction=0.025"});
  const fs::path dir = temp_dir("openfoam-thick");
  const OpenfoamCase c = write_openfoam_case(s, dir.string());
  const std::string mesh = read_file(dir / "system/blockMeshDict");
  EXPECT_NE(mesh.find("(15 45 1)"), std::string::npos);  // still one cell deep
  EXPECT_EQ(mesh.find("type empty;"), std::string::npos);
  const auto front = mesh.find("    frontAndBack");
  ASSERT_NE(front, std::string::npos);
  EXPECT_EQ(mesh.find("type wall;", front), mesh.find("type", front));
  const std::string u = read_file(dir / "0/U.air"), p = read_file(dir / "0/p");
  EXPECT_NE(u.find("frontAndBack\n    {\n        type            slip;"), std::string::npos) << u;
  EXPECT_NE(p.find("frontAndBack\n    {\n        type            fixedFluxPressure;"),
            std::string::npos)
      << p;

  const std::vector<Point> pts = read_points(dir / "constant/kinematicCloudPositions");
  const Particles start = place_particles(s);
  ASSERT_EQ(pts.size(), start.size());
  std::set<double> depths;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(pts[i].x, start.x[i]) << i;
    ASSERT_EQ(pts[i].y, start.y[i]) << i;
    ASSERT_EQ(pts[i].z, start.z[i]) << i;
    EXPECT_GE(pts[i].z, 0.002 - 1e-15) << i;
    EXPECT_LE(pts[i].z, 0.010 + 1e-15) << i;
    depths.insert(pts[i].z);
  }
  EXPECT_GE(depths.size(), 3u);  // the lattice fills the depth
  auto noted = [&c](const std::string& what) {
    return std::any_of(c.notes.begin(), c.notes.end(),
                       [&](const std::string& n) { return n.rfind(what, 0) == 0; });
  };
  EXPECT_TRUE(noted("front and back: walls for the spheres"));
  EXPECT_TRUE(noted("rolling resistance: DPMFoam's collision models have none"));
  EXPECT_NE(read_file(dir / "constant/kinematicCloudProperties").find("contact.rolling_friction = 0.025"),
            std::string::npos);

  // The monolayer's case keeps its empty patches and says nothing of rolling resistance.
  const OpenfoamCase flat =
      write_openfoam_case(scene("packing.toml", {"particles.count=300"}), (dir / "flat").string());
  EXPECT_NE(read_file(dir / "flat/system/blockMeshDict").find("type empty;"), std::string::npos);
  EXPECT_FALSE(std::any_of(flat.notes.begin(), flat.notes.end(), [](const std::string& n) {
    return n.rfind("rolling resistance", 0) == 0;
  }));

  const Settings hertz = scene(
      "packing.toml", {"domain.thickness=0.012", "particles.count=300", "contact.law=hertz_mindlin",
                       "contact.youngs_modulus=1e7", "contact.poisson_ratio=0.3",
                       "contact.restitution=0.9"});
  try {
    write_openfoam_case(hertz, (dir / "hertz").string());
    ADD_FAILURE() << "a Hertz-Mindlin scene was exported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("contact.law"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "hertz"));
}

// The normal spring is ours exactly (for pairs and walls, by OpenFOAM's own formulas); the
// dashpot's restitution is ours at the reference speed.
TEST(OpenfoamExport, CollisionLawReproducesTheSpringAndTheRestitution) {
  const Settings s = scene("xu_yu_1997.toml");
  const DpmCollisionLaw law = dpm_collision_law(s);
  const double d = 0.004, m = paper_mass();
  const double nu = law.poissons_ratio, nw = law.wall_poissons_ratio;
  // PairSpringSliderDashpot: E* = E / (2 (1 - nu^2)), R = d/4; wall: 1/E* = sum (1 - nu^2)/E.
  const double kn_pair =
      4.0 / 3.0 * std::sqrt(d / 4.0) * law.youngs_modulus / (2.0 * (1 - nu * nu));
  const double kn_wall =
      4.0 / 3.0 * std::sqrt(d / 2.0) /
      ((1 - nu * nu) / law.youngs_modulus + (1 - nw * nw) / law.wall_youngs_modulus);
  EXPECT_NEAR(kn_pair, 5e4, 1e-9 * 5e4);
  EXPECT_NEAR(kn_wall, 5e4, 1e-9 * 5e4);
  EXPECT_EQ(law.b, 1.0);
  EXPECT_EQ(law.mu, 0.3);
  // Our restitution (model.md: 0.895 against a wall) and DPMFoam's at 1 m/s with the alphas.
  EXPECT_NEAR(law.restitution_wall, analytic_restitution(5e4, 0.15, m), 1e-12);
  EXPECT_NEAR(law.restitution_wall, 0.895, 0.001);
  EXPECT_NEAR(law.restitution_pair, analytic_restitution(5e4, 0.15, m / 2), 1e-12);
  EXPECT_NEAR(dpm_restitution(5e4, m, law.alpha_wall, 1.0), law.restitution_wall, 1e-6);
  EXPECT_NEAR(dpm_restitution(5e4, m / 2, law.alpha_pair, 1.0), law.restitution_pair, 1e-6);
  // delta^(1/4): slower impacts lose less, faster ones more.
  EXPECT_GT(law.restitution_pair_slow, law.restitution_pair);
  EXPECT_LT(law.restitution_pair_fast, law.restitution_pair);
  // No sub-cycling: our steps per pair contact, pi sqrt(m / 2k) / dt = 6.3.
  EXPECT_EQ(law.resolution_steps, 6);
}

// dpm_restitution against closed forms: no damping is elastic; weak damping loses energy
// 2 c I, I = int_0^pi sin^(1/4) cos^2 = Gamma(5/8) Gamma(3/2) / Gamma(17/8), so
// e = sqrt(1 - 2 c I) with c = alpha (v / omega)^(1/4); and the linear law's closed form.
TEST(OpenfoamExport, RestitutionIntegratorAgainstClosedForms) {
  const double k = 5e4, m = paper_mass(), v = 1.0, omega = std::sqrt(k / m);
  EXPECT_NEAR(dpm_restitution(k, m, 0.0, v), 1.0, 1e-9);
  const double c = 1e-3, alpha = c / std::pow(v / omega, 0.25);
  const double integral = std::tgamma(0.625) * std::tgamma(1.5) / std::tgamma(2.125);
  EXPECT_NEAR(dpm_restitution(k, m, alpha, v), std::sqrt(1.0 - 2.0 * c * integral), 2e-6);
  EXPECT_NEAR(restitution_from_damping(k, 0.15, m), analytic_restitution(k, 0.15, m), 1e-15);
}

// Wen-Yu is the drag nearest fluidbed's Di Felice where the bed sits near minimum fluidization.
TEST(OpenfoamExport, WenYuIsNearDiFeliceInThePackedBed) {
  const Settings s = scene("xu_yu_1997.toml");
  EXPECT_NEAR(wen_yu_over_di_felice(s, 0.42, 1.9), 1.0, 0.1);
  EXPECT_NEAR(wen_yu_over_di_felice(s, 0.45, 1.0), 1.0, 0.15);
}

TEST(OpenfoamExport, UniformInletAndTopWall) {
  const Settings s = scene("xu_yu_1997.toml", {"particles.placement=lattice", "inlet.kind=uniform",
                                               "domain.top_wall=true", "particles.count=100"});
  const fs::path dir = temp_dir("openfoam-uniform");
  write_openfoam_case(s, dir.string());
  const std::string mesh = read_file(dir / "system/blockMeshDict");
  EXPECT_NE(mesh.find("(15 45 1)"), std::string::npos);
  EXPECT_EQ(mesh.find("    bottom"), std::string::npos);  // the whole bottom is the inlet
  EXPECT_NE(mesh.find("    outlet  // the gas leaves at the top; a wall for the particles"),
            std::string::npos);
  EXPECT_NE(read_file(dir / "0/U.air").find("inletVelocity   uniform (0 2.8 0)"),
            std::string::npos);
}

TEST(OpenfoamExport, RefusesWhatTheCaseCannotExpress) {
  const fs::path dir = temp_dir("openfoam-refused");
  EXPECT_THROW(write_openfoam_case(scene("drop.toml"), (dir / "drop").string()), InputError);
  EXPECT_THROW(write_openfoam_case(scene("packing.toml", {"particles.frozen=true"}),
                                   (dir / "frozen").string()),
               InputError);
  EXPECT_FALSE(fs::exists(dir / "drop"));
  EXPECT_FALSE(fs::exists(dir / "frozen"));
  // On the command line: one line, exit 2.
  const std::string assets = std::string(FLUIDBED_ASSET_DIR) + "/scenes/";
  const CommandResult nogas = run_fluidbed(
      "export " + assets + "drop.toml --to openfoam " + (dir / "cli").string(), "of-nogas");
  EXPECT_EQ(nogas.status, 2);
  EXPECT_NE(nogas.err.find("no [gas]"), std::string::npos) << nogas.err;
  EXPECT_EQ(std::count(nogas.err.begin(), nogas.err.end(), '\n'), 1) << nogas.err;
  const CommandResult unknown = run_fluidbed(
      "export " + assets + "packing.toml --to fluent " + (dir / "cli").string(), "of-unknown");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("known: liggghts, openfoam"), std::string::npos) << unknown.err;
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1) << unknown.err;
  EXPECT_FALSE(fs::exists(dir / "cli"));
}

// The exported packing (300 spheres, gas at rest) runs 100 steps on 2 MPI processes: the run
// ends, every sphere is still there, and each has fallen g t^2 / 2 within 5 % (DPMFoam's
// implicit Euler parcel step adds 1 %, the gas that the falling spheres set moving up to 1.5 %
// more and nudges them sideways by under 1 um), except any on the bottom row, which rest on the
// floor.
TEST(OpenfoamRun, ExportedPackingRunsInParallel) {
  REQUIRE_OPENFOAM();
  const Settings s = scene("packing.toml", {"particles.count=300", "time.end=0.0015"});
  const fs::path dir = temp_dir("openfoam-run-packing");
  write_openfoam_case(s, dir.string());
  const std::vector<Point> end = run_in_parallel_to_end(dir, 0.0015);
  ASSERT_EQ(end.size(), 300u);
  const Particles start = place_particles(s);
  const double time = 100 * 1.5e-5, fall = 0.5 * 9.81 * time * time, r = 0.002;
  int matched = 0, resting = 0;
  for (const Point& q : end) {
    EXPECT_NEAR(q.z, 0.002, 1e-12);
    for (std::size_t i = 0; i < start.size(); ++i) {
      if (std::fabs(start.x[i] - q.x) > 2e-6 || start.y[i] - q.y < -1e-6 || start.y[i] - q.y > 1e-4)
        continue;
      ++matched;
      const bool floor = start.y[i] == r;
      resting += floor;
      EXPECT_NEAR(start.y[i] - q.y, floor ? 0.0 : fall, floor ? 1e-6 : 0.05 * fall) << i;
      break;
    }
  }
  EXPECT_EQ(matched, 300);
}

// The paper's jetted bed (lattice start, 300 spheres) runs 100 steps on one process: the jet
// boundary and the wall-type inlet patch work, and no sphere is lost.
TEST(OpenfoamRun, JettedBedRunsSerial) {
  REQUIRE_OPENFOAM();
  const Settings s = scene(
      "xu_yu_1997.toml", {"particles.placement=lattice", "particles.count=300", "time.end=0.0015"});
  const fs::path dir = temp_dir("openfoam-run-jet");
  write_openfoam_case(s, dir.string());
  ASSERT_EQ(run_allrun(dir, "serial"), 0) << read_file(dir / "allrun.out");
  const std::string log = read_file(dir / "log.DPMFoam");
  EXPECT_NE(log.find("\nEnd"), std::string::npos);
  EXPECT_EQ(last_parcel_count(log), 300);
  const fs::path t = last_time(dir);
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(read_points(t / "lagrangian/kinematicCloud/positions").size(), 300u);
  // The gas comes in through the slot at the jet's superficial 42 m/s: the face's interstitial
  // velocity is 42 / porosity of the cell above it (a few spheres there: 42-48 m/s).
  const double u = patch_value(read_file(t / "U.air"), "inlet", 1);
  const double alpha = patch_value(read_file(t / "alpha.air"), "inlet", 0);
  EXPECT_GT(alpha, 0.9);
  EXPECT_LE(alpha, 1.0);
  EXPECT_NEAR(u * alpha, 42.0, 1e-6 * 42.0);
}

// The thick slab's case (300 spheres 3 deep, gas at rest) runs 100 steps on 2 MPI processes:
// every sphere is still there, each has fallen g t^2 / 2 within 5 % (as the monolayer's above)
// or rests on the floor, and each keeps its depth: the front and back walls hold the spheres
// that touch them and push none.
TEST(OpenfoamRun, ThickSlabRunsInParallel) {
  REQUIRE_OPENFOAM();
  const Settings s =
      scene("packing.toml", {"domain.thickness=0.012", "particles.count=300", "time.end=0.0015"});
  const fs::path dir = temp_dir("openfoam-run-thick");
  write_openfoam_case(s, dir.string());
  const std::vector<Point> end = run_in_parallel_to_end(dir, 0.0015);
  ASSERT_EQ(end.size(), 300u);
  const Particles start = place_particles(s);
  const double time = 100 * 1.5e-5, fall = 0.5 * 9.81 * time * time, r = 0.002;
  int matched = 0;
  for (const Point& q : end) {
    for (std::size_t i = 0; i < start.size(); ++i) {
      if (std::fabs(start.x[i] - q.x) > 2e-6 || std::fabs(start.z[i] - q.z) > 2e-6 ||
          start.y[i] - q.y < -1e-6 || start.y[i] - q.y > 1e-4)
        continue;
      ++matched;
      const bool floor = start.y[i] == r;
      EXPECT_NEAR(start.y[i] - q.y, floor ? 0.0 : fall, floor ? 1e-6 : 0.05 * fall) << i;
      EXPECT_NEAR(q.z, start.z[i], 1e-6) << i;
      break;
    }
  }
  EXPECT_EQ(matched, 300);
}
