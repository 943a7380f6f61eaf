// `fluidbed check`'s derived figures against hand calculations, its refusals, and the refusals
// every running command applies before its first step; directories, devices and unreadable files
// given as a scene, script or state file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

std::string scene(const std::string& name) {
  return std::string(FLUIDBED_ASSET_DIR) + "/scenes/" + name;
}

int lines(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TEST(SceneChecks, FiguresOfThePapersBedByHand) {
  const Settings s = load_scene(scene("xu_yu_1997.toml"));
  const SceneCheck c = check_scene(s);
  const SceneFigures& f = c.figures;
  // m = 2700 pi 0.004^3 / 6 = 9.048e-5 kg; t_c = pi sqrt(9.048e-5 / 50000) = 1.336e-4 s.
  EXPECT_NEAR(f.particle_mass, 9.048e-5, 1e-8);
  EXPECT_NEAR(f.contact_duration_wall, 1.3364e-4, 1e-8);
  EXPECT_NEAR(f.contact_duration_pair, 1.3364e-4 / std::sqrt(2.0), 1e-8);
  EXPECT_NEAR(f.dt_over_tc_wall, 1.5e-5 / 1.3364e-4, 1e-4);
  // z = 0.15 / (2 sqrt(50000 x 9.048e-5)) = 0.03526; e = exp(-pi z / sqrt(1 - z^2)) = 0.8951.
  EXPECT_NEAR(f.restitution_wall, 0.8951, 1e-4);
  // Pair: m / 2, z = 0.04987, e = 0.8548.
  EXPECT_NEAR(f.restitution_pair, 0.8548, 1e-4);
  // W/A = 2400 x 9.048e-5 x 9.81 / (0.15 x 0.004) = 3550 Pa.
  EXPECT_NEAR(f.weight_per_area, 3550.4, 0.5);
  ASSERT_TRUE(f.gas);
  // Jet: 2.8 x 0.15 / 0.01 = 42 m/s.
  EXPECT_NEAR(f.jet_velocity, 42.0, 1e-9);
  // Cells: 10 mm x 20 mm against 4 mm.
  EXPECT_NEAR(f.cell_dx_over_d, 2.5, 1e-12);
  EXPECT_NEAR(f.cell_dy_over_d, 5.0, 1e-12);
  // CFL: 42 x 1.5e-5 / 0.01 = 0.063.
  EXPECT_NEAR(f.gas_cfl_at_jet, 0.063, 1e-9);
  EXPECT_TRUE(c.refusals.empty());
}

TEST(SceneChecks, WenYuForGlassInAirByHand) {
  // 4 mm glass (2700 kg/m^3) in air (1.205 kg/m^3, 1.8e-5 Pa s): Ar = 0.004^3 x 1.205 x 2698.8 x
  // 9.81 / (1.8e-5)^2 = 6.302e6; Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7 = 474.5;
  // U_mf = 474.5 x 1.8e-5 / (1.205 x 0.004) = 1.772 m/s.
  EXPECT_NEAR(wen_yu_umf(0.004, 2700.0, 1.205, 1.8e-5, 9.81), 1.772, 2e-3);
  // Lighter particles fluidize sooner; no buoyancy difference, no fluidization velocity.
  EXPECT_LT(wen_yu_umf(0.004, 1350.0, 1.205, 1.8e-5, 9.81), 1.772);
  EXPECT_EQ(wen_yu_umf(0.004, 1.205, 1.205, 1.8e-5, 9.81), 0.0);
}

TEST(SceneChecks, GasStepAndCflFollowTheCoupling) {
  Settings s = load_scene(scene("xu_yu_1997.toml"), {"coupling.particle_steps_per_gas_step=4"});
  const SceneFigures f = check_scene(s).figures;
  EXPECT_NEAR(f.gas_dt, 6e-5, 1e-15);
  EXPECT_NEAR(f.gas_cfl_at_jet, 42.0 * 6e-5 / 0.01, 1e-9);
  s.inlet.kind = InletKind::Uniform;
  EXPECT_NEAR(check_scene(s).figures.jet_velocity, 2.8, 1e-12);
}

TEST(SceneChecks, AStepBeyondTheMeasuredLimitIsRefused) {
  const Settings s = load_scene(scene("xu_yu_1997.toml"), {"time.dt=1e-3"});
  const SceneCheck c = check_scene(s);
  ASSERT_EQ(c.refusals.size(), 1u);
  EXPECT_NE(c.refusals[0].find("time.dt = 0.001 s"), std::string::npos) << c.refusals[0];
  EXPECT_NE(c.refusals[0].find("0.0001336 s"), std::string::npos) << c.refusals[0];
  EXPECT_THROW(refuse_unsafe_scene(s), InputError);
  // Every integrator's limit is below 1.5 t_c, the study's largest step, and above the paper's.
  for (Integrator i :
       {Integrator::Newmark, Integrator::VelocityVerlet, Integrator::SymplecticEuler}) {
    const StepLimits l = measured_step_limits(i);
    EXPECT_LT(l.unstable, 1.5);
    EXPECT_GT(l.largest_stable, 1.5e-5 / 1.3364e-4);
    EXPECT_LE(l.accurate, l.largest_stable);
    EXPECT_LT(l.largest_stable, l.unstable);
  }
}

TEST(SceneChecks, CheckPrintsEveryShippedScenesFiguresAndExitsZero) {
  for (const char* name : {"drop.toml", "ideal.toml", "packing.toml", "teaching.toml", "wide.toml",
                           "xu_yu_1997.toml", "van_wachem_2001.toml"}) {
    const CommandResult r = run_fluidbed("check " + scene(name), "check");
    EXPECT_EQ(r.status, 0) << name << "\n" << r.out << r.err;
    for (const char* figure :
         {"particle mass", "contact duration, wall", "contact duration, pair", "dt / t_c",
          "restitution, wall", "restitution, pair", "bed weight per area", "slab depth"})
      EXPECT_NE(r.out.find(figure), std::string::npos) << name << ": " << figure << "\n" << r.out;
    // Only the thick slab moves its particles in 3D.
    EXPECT_EQ(r.out.find("particles move in 3D") != std::string::npos,
              std::string(name) == "van_wachem_2001.toml")
        << name << "\n" << r.out;
    if (std::string(name) != "drop.toml") {
      for (const char* figure : {"jet velocity", "U_mf, Wen-Yu", "gas cell / d", "gas CFL"})
        EXPECT_NE(r.out.find(figure), std::string::npos) << name << ": " << figure << "\n" << r.out;
    }
    EXPECT_EQ(r.out.find("refused"), std::string::npos) << name << "\n" << r.out;
  }
  // The smoothed void fraction's length in cells and diameters (van Wachem's 5 mm cells, 1.545 mm
  // spheres: 1.5 mm is 0.3 cells and 0.971 d).
  const CommandResult r = run_fluidbed(
      "check " + scene("van_wachem_2001.toml") +
          " --set coupling.void_fraction=smoothed --set coupling.void_fraction_length=0.0015",
      "check-smoothed");
  EXPECT_NE(r.out.find("smoothed over 0.0015 m (0.3 cells wide, 0.3 high; 0.971 d)"),
            std::string::npos)
      << r.out;
}

TEST(SceneChecks, CheckAndRunRefuseTheLargeStepInOneLine) {
  const std::string bed = scene("xu_yu_1997.toml");
  const CommandResult c = run_fluidbed("check " + bed + " --set time.dt=1e-3", "check-dt");
  EXPECT_EQ(c.status, 2) << c.out << c.err;
  EXPECT_NE(c.out.find("refused: time.dt = 0.001 s"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("contact duration"), std::string::npos) << c.out;
  const auto dir = temp_dir("check-run");
  for (const std::string verb : {"run", "sweep", "view", "bench"}) {
    const CommandResult r =
        run_fluidbed(verb + " " + bed + " --set time.dt=1e-3 --out " + (dir / verb).string(), verb);
    EXPECT_EQ(r.status, 2) << verb << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << verb << "\n" << r.err;
    EXPECT_NE(r.err.find("time.dt = 0.001 s"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("contact duration t_c = 0.0001336 s"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("largest stable"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / verb / "summary.json")) << verb;
  }
}

TEST(SceneChecks, DirectoriesDevicesAndUnreadableFilesAreOneLineErrors) {
  const auto dir = temp_dir("check-paths");
  std::filesystem::create_directories(dir / "folder.toml");
  const std::string fifo = (dir / "pipe.toml").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::vector<std::string> bad = {(dir / "folder.toml").string(), "/dev/null", fifo};
  // Root reads a file of mode 000; anyone else is refused it.
  const std::string locked = (dir / "locked.toml").string();
  write_file(locked, "[particles]\ncount = 1\n");
  ::chmod(locked.c_str(), 0);
  if (::geteuid() != 0) bad.push_back(locked);
  const std::string drop = scene("drop.toml");
  const auto out = (dir / "o").string();
  int k = 0;
  for (const std::string& path : bad) {
    const std::string tag = "path" + std::to_string(k++);
    // As the scene.
    for (const std::string verb : {"run", "check"}) {
      const CommandResult r =
          run_fluidbed(verb + " " + path + (verb == "run" ? " --out " + out : ""), tag);
      EXPECT_EQ(r.status, 2) << verb << " " << path << "\n" << r.out << r.err;
      EXPECT_EQ(lines(r.err), 1) << r.err;
      EXPECT_NE(r.err.find("cannot read scene file " + path), std::string::npos) << r.err;
    }
    // As the viewer's script.
    const CommandResult v =
        run_fluidbed("view " + drop + " --script " + path + " --out " + out, tag + "v");
    EXPECT_EQ(v.status, 2) << path << "\n" << v.err;
    EXPECT_EQ(lines(v.err), 1) << v.err;
    EXPECT_NE(v.err.find("cannot read script " + path), std::string::npos) << v.err;
    // As the state file.
    const auto state_scene = dir / ("state" + std::to_string(k) + ".toml");
    write_file(state_scene,
               "[particles]\ncount = 1\nplacement = \"state\"\nstate_file = \"" + path + "\"\n");
    const CommandResult s =
        run_fluidbed("run " + state_scene.string() + " --out " + out, tag + "s");
    EXPECT_EQ(s.status, 2) << path << "\n" << s.err;
    EXPECT_EQ(lines(s.err), 1) << s.err;
    EXPECT_NE(s.err.find("cannot read state file " + path), std::string::npos) << s.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "o" / "summary.json"));
}

// The likely cause follows what crossed its limit: a failure of the contacts names the step's
// warning; a gas CFL number names the gas velocity, never the particle step.
TEST(SceneChecks, AFailureNamesWhatCrossedItsLimitAsItsLikelyCause) {
  // The teaching bed's earlier settings (6.708e-5 s at 10,000 N/m, the gas every 2 steps): a step
  // just past the largest step measured stable, a warning, no refusal.
  Settings teaching = load_scene(scene("teaching.toml"),
                                 {"contact.stiffness=10000", "contact.damping=0.067082039324993681",
                                  "time.dt=6.708e-5", "coupling.particle_steps_per_gas_step=2"});
  ASSERT_NO_THROW(refuse_unsafe_scene(teaching));
  const std::string overlap = "porosity 0.01 outside (0, 1] in gas cell (3, 0) at t = 0.1 s";
  EXPECT_NE(failure_hint(overlap).find("; likely cause: time.dt = "), std::string::npos)
      << failure_hint(overlap);
  EXPECT_EQ(failure_hint(overlap).find('\n'), std::string::npos);
  // The viewer's fault: 5.2 m/s through the teaching bed's jet failed on the gas CFL number at
  // its first gas step, and the message blamed time.dt and the contact duration.
  teaching.inlet.superficial_velocity = 5.2;
  ASSERT_NO_THROW(refuse_unsafe_scene(teaching));
  const std::string cfl =
      "gas: CFL number 1.046 > 1 (velocity 78 m/s on the bottom face of cell (7, 0), dt = "
      "0.0001342 s): the gas enters more than a cell in one gas step at t = 0 s (gas step 1)";
  const std::string h = failure_hint(cfl);
  EXPECT_EQ(h.rfind("; likely cause: the gas velocity: the jet enters at 78 m/s "
                    "(inlet.superficial_velocity = 5.2 m/s)",
                    0),
            0u)
      << h;
  EXPECT_NE(h.find("lower inlet.superficial_velocity"), std::string::npos) << h;
  EXPECT_EQ(h.find("contact duration"), std::string::npos) << h;
  // A control (Python's superficial_velocity) raised the velocity from the scene's: the hint
  // names the one in use and the jet's at it (in proportion: 78 m/s at 5.2, 150 at 10).
  const std::string raised = failure_hint(cfl, 10.0);
  EXPECT_EQ(raised.rfind("; likely cause: the gas velocity: the jet enters at 150 m/s (10 m/s "
                         "superficial in use; the scene's inlet.superficial_velocity is 5.2 m/s)",
                         0),
            0u)
      << raised;
  EXPECT_EQ(failure_hint(cfl, 5.2), h);
  refuse_unsafe_scene(load_scene(scene("xu_yu_1997.toml")));
  EXPECT_EQ(failure_hint(overlap), "");
}
