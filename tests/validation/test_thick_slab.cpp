// The particle step in three dimensions (a slab thicker than one diameter) against closed forms:
// an oblique impact on the front wall, two spheres colliding off the plane, a sphere sliding then
// rolling at 5/7 in any direction of the floor, rolling resistance bringing one to rest; and a
// small thick slab packed on one and two threads, with the linear law and with Hertz-Mindlin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "core/text_format.hpp"
#include "dem/dem_solver.hpp"
#include "io/openfoam_export.hpp"
#include "scene/scene_loader.hpp"
#include "sim/model_params.hpp"
#include "sim/placement.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;

namespace {

// A sphere of the paper's size at (x, y, z) moving at (vx, vy, vz) with spin (wx, wy, wz).
struct Sphere3 {
  double x, y, z, vx, vy, vz, wx = 0.0, wy = 0.0, wz = 0.0;
};

Particles make_spheres(std::initializer_list<Sphere3> list) {
  Particles p;
  p.resize(list.size());
  p.add_depth(0.0);
  std::size_t i = 0;
  for (const Sphere3& q : list) {
    p.set_sphere(i, 0.004, 2700.0);
    p.x[i] = q.x;
    p.y[i] = q.y;
    p.z[i] = q.z;
    p.vx[i] = q.vx;
    p.vy[i] = q.vy;
    p.vz[i] = q.vz;
    p.wx[i] = q.wx;
    p.wy[i] = q.wy;
    p.w[i] = q.wz;
    ++i;
  }
  return p;
}

// A box of width x height x thickness (m) with the front and back walls as contacts.
Settings thick_box(double width, double height, double thickness, double dt) {
  Settings s;
  s.domain.width = width;
  s.domain.height = height;
  s.domain.thickness = thickness;
  s.time.dt = dt;
  return s;
}

// `count` spheres on the random lattice (random depths) of a box `width` wide, 0.2 m high and
// `thickness` deep, at the paper's step.
Settings thick_bed(int count, double width, double thickness, std::uint64_t seed) {
  Settings s = thick_box(width, 0.2, thickness, Settings{}.time.dt);
  s.particles.count = count;
  s.particles.seed = seed;
  return s;
}

}  // namespace

TEST(ThickSlab, ObliqueImpactOnTheFrontWallGivesTheLinearModelsRebound) {
  // 0.5 m/s into the front wall (z = 0) and 2 m/s along the wall in a direction a of the x-y
  // plane, no gravity. Normal: the restitution of a mass m against a wall. Tangential: the
  // contact point slides throughout (2 m/s is more than 7/2 mu (1 + e) 0.5 = 1.0 m/s), so the
  // friction impulse is mu times the springs' normal impulse, mu m (1 + e) v_n (the dashpot's
  // impulse is eta (delta_end - delta_start) = 0): the sphere loses mu (1 + e) v_n along the
  // wall and spins up to R w = 5/2 mu (1 + e) v_n, in the plane of n and the sliding direction.
  const double vn = 0.5, vt = 2.0, mu = 0.3, a = 0.7;
  const double e = analytic_restitution(50000.0, 0.15, paper_mass());
  for (const char* integrator : {"newmark", "velocity_verlet", "symplectic_euler"}) {
    Settings s = thick_box(0.2, 0.2, 0.02, 1.5e-7);
    s.physics.gravity = 0.0;
    s.time.integrator = parse_option<Integrator>("time.integrator", integrator);
    const double c = std::cos(a), sn = std::sin(a);
    DemSolver dem(dem_params_for(s),
                  make_spheres({{0.1, 0.1, 0.0021, vt * c, vt * sn, -vn}}));
    const auto steps = static_cast<std::int64_t>(4e-4 / 1.5e-7);  // 0.2 ms to touch, 0.1 in
    for (std::int64_t k = 0; k < steps; ++k) dem.step();
    const Particles& p = dem.particles();
    const double r = 0.002;
    const double lost = mu * (1.0 + e) * vn;
    const double along = p.vx[0] * c + p.vy[0] * sn, across = -p.vx[0] * sn + p.vy[0] * c;
    // The spin: friction along -t at the contact point -R z turns the sphere about
    // (-z) x (-t) = z x t = (-sin a, cos a, 0), towards rolling.
    const double spin = p.wx[0] * (-sn) + p.wy[0] * c;
    std::printf("%-17s e = %.5f (closed form %.5f), v_t = %.5f (%.5f), R w = %.5f (%.5f)\n",
                integrator, p.vz[0] / vn, e, along, vt - lost, spin * r, 2.5 * lost);
    EXPECT_NEAR(p.vz[0] / vn, e, 0.002) << integrator;
    EXPECT_NEAR(along, vt - lost, 0.01 * lost) << integrator;
    EXPECT_NEAR(across, 0.0, 1e-12) << integrator;
    EXPECT_NEAR(spin * r, 2.5 * lost, 0.01 * 2.5 * lost) << integrator;
    EXPECT_NEAR(p.w[0], 0.0, 1e-9) << integrator;  // no spin about the wall's normal
  }
}

TEST(ThickSlab, OffPlaneCollisionConservesMomentumAndAngularMomentum) {
  // Two spheres meeting along a line of centres out of every coordinate plane, with spins and
  // a sliding, then sticking contact. Momentum is conserved to round-off. Angular momentum
  // about the origin changes only by what eq 2's torque arms leave: the torques use the radii
  // R_i, R_j while the centres are L < R_i + R_j apart, so the pair's torques sum to
  // (R - L) n x F_t; the test bounds the change by the largest overlap times the tangential
  // impulse, and the rest is round-off.
  Settings s = thick_box(0.2, 0.2, 0.04, 1.5e-7);
  s.physics.gravity = 0.0;
  const double gap = 0.0045;
  const double d[3] = {0.6, 0.48, 0.64};  // unit line of centres
  DemSolver dem(dem_params_for(s),
                make_spheres({{0.1, 0.1, 0.02, 0.9, 0.2, 0.5, 30.0, -20.0, 50.0},
                              {0.1 + gap * d[0], 0.1 + gap * d[1], 0.02 + gap * d[2], -0.3, 0.4,
                               -0.6, -10.0, 40.0, 0.0}}));
  const Particles& p = dem.particles();
  auto momentum = [&](int c) {
    double m = 0.0;
    for (std::size_t i = 0; i < 2; ++i)
      m += p.mass[i] * (c == 0 ? p.vx[i] : c == 1 ? p.vy[i] : p.vz[i]);
    return m;
  };
  auto angular = [&](int c) {
    double l = 0.0;
    for (std::size_t i = 0; i < 2; ++i) {
      const Vec3 r{p.x[i], p.y[i], p.z[i]}, v{p.vx[i], p.vy[i], p.vz[i]};
      const Vec3 h = p.mass[i] * cross(r, v) + (1.0 / p.inv_inertia[i]) * Vec3{p.wx[i], p.wy[i], p.w[i]};
      l += c == 0 ? h.x : c == 1 ? h.y : h.z;
    }
    return l;
  };
  double m0[3], l0[3];
  for (int c = 0; c < 3; ++c) m0[c] = momentum(c), l0[c] = angular(c);
  double max_gap = 0.0, impulse = 0.0;  // m, N s
  bool touched = false;
  const auto steps = static_cast<std::int64_t>(2e-3 / 1.5e-7);
  for (std::int64_t k = 0; k < steps; ++k) {
    dem.step();
    const double dx = p.x[1] - p.x[0], dy = p.y[1] - p.y[0], dz = p.z[1] - p.z[0];
    const double L = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (L < 0.004) {
      touched = true;
      max_gap = std::max(max_gap, 0.004 - L);
      // |n x F_t| = |F_t|: the torque on sphere 0 is R_0 n x F_t.
      const double t = std::sqrt(p.torque_x[0] * p.torque_x[0] + p.torque_y[0] * p.torque_y[0] +
                                 p.torque[0] * p.torque[0]);
      impulse += t / 0.002 * 1.5e-7;
    }
  }
  ASSERT_TRUE(touched);
  const double scale = paper_mass() * 1.0;
  double worst_l = 0.0;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(momentum(c), m0[c], 1e-15 * scale) << c;
    worst_l = std::max(worst_l, std::fabs(angular(c) - l0[c]));
  }
  const double bound = max_gap * impulse;
  std::printf("momentum to round-off; angular momentum changed by %.3e N m s, the arms' bound "
              "(largest overlap %.3e m x tangential impulse %.3e N s) %.3e\n",
              worst_l, max_gap, impulse, bound);
  EXPECT_LE(worst_l, bound + 1e-18);
  EXPECT_GT(impulse, 0.0);  // the contact had friction to test
}

TEST(ThickSlab, SlidingSphereEndsRollingAtFiveSeventhsInAnyDirection) {
  // The floor is the x-z plane: released touching it at 1 m/s along (cos a, 0, sin a), no spin.
  const double a = 0.9;
  for (const char* integrator : {"newmark", "velocity_verlet", "symplectic_euler"}) {
    Settings s = thick_box(1.0, 0.2, 1.0, 1.5e-5);
    s.time.integrator = parse_option<Integrator>("time.integrator", integrator);
    DemSolver dem(dem_params_for(s),
                  make_spheres({{0.02, 0.002, 0.1, std::cos(a), 0.0, std::sin(a)}}));
    const auto steps = static_cast<std::int64_t>(0.3 / s.time.dt);
    for (std::int64_t k = 0; k < steps; ++k) dem.step();
    const Particles& p = dem.particles();
    const double v = std::hypot(p.vx[0], p.vz[0]);
    // Rolling: the contact point, at -R y, is at rest: v + w x (-R y) = 0.
    const Vec3 slip = Vec3{p.vx[0], 0.0, p.vz[0]} + cross(Vec3{p.wx[0], p.wy[0], p.w[0]},
                                                        Vec3{0.0, -0.002, 0.0});
    std::printf("%-17s v / v0 = %.5f, slip %.2e m/s, direction %.6f rad\n", integrator, v,
                std::hypot(slip.x, slip.z), std::atan2(p.vz[0], p.vx[0]));
    EXPECT_NEAR(v, 5.0 / 7.0, 0.02 * 5.0 / 7.0) << integrator;
    EXPECT_LT(std::hypot(slip.x, slip.z), 0.01 * v) << integrator;
    EXPECT_NEAR(std::atan2(p.vz[0], p.vx[0]), a, 1e-9) << integrator;
  }
}

TEST(ThickSlab, WallFrictionSlowsASlidingSphereAtGammaWG) {
  // Sliding on the floor along (cos a, 0, sin a) with the walls' own friction gamma_w = 0.1 (the
  // particles' is 0.3): until it rolls, at t* = 2 v0 / (7 gamma_w g) = 0.29 s, its speed falls as
  // v0 - gamma_w g t (closed form); after 0.2 s, 0.804 m/s.
  const double a = 0.9, mu = 0.1, t = 0.2;
  Settings s = thick_box(1.0, 0.2, 1.0, 1.5e-5);
  s.contact.wall_friction = mu;
  DemSolver dem(dem_params_for(s), make_spheres({{0.02, 0.002, 0.1, std::cos(a), 0.0, std::sin(a)}}));
  const auto steps = static_cast<std::int64_t>(std::llround(t / s.time.dt));
  for (std::int64_t k = 0; k < steps; ++k) dem.step();
  const Particles& p = dem.particles();
  const double v = std::hypot(p.vx[0], p.vz[0]), closed = 1.0 - mu * s.physics.gravity * t;
  std::printf("after %.1f s: v = %.5f m/s (closed form %.5f)\n", t, v, closed);
  EXPECT_NEAR(v, closed, 0.005 * closed);
  EXPECT_NEAR(std::atan2(p.vz[0], p.vx[0]), a, 1e-9);
}

TEST(ThickSlab, RollingResistanceStopsASphereAtTheClosedFormDistanceInAnyDirection) {
  // As Rolling.ResistanceStopsARollingSphereAtTheClosedFormDistance, along (cos a, 0, sin a):
  // 7 v0^2 / (10 mu_r g) = 28.5 mm.
  const double v0 = 0.2, mu_r = 0.1, a = -0.5, r = 0.002;
  Settings s = thick_box(1.0, 0.2, 1.0, 1.5e-5);
  s.contact.rolling_friction = mu_r;
  const double g = s.physics.gravity;
  const double y0 = r - paper_mass() * g / s.contact.stiffness;
  const double c = std::cos(a), sn = std::sin(a);
  // Rolling: w x (-R y) = -v, so w = (v_z, 0, -v_x) / R.
  DemSolver dem(dem_params_for(s), make_spheres({{0.02, y0, 0.5, v0 * c, 0.0, v0 * sn,
                                                  v0 * sn / r, 0.0, -v0 * c / r}}));
  const auto steps = static_cast<std::int64_t>(0.6 / s.time.dt);
  for (std::int64_t k = 0; k < steps; ++k) dem.step();
  const Particles& p = dem.particles();
  const double distance = std::hypot(p.x[0] - 0.02, p.z[0] - 0.5);
  const double expected = 7.0 * v0 * v0 / (10.0 * mu_r * g);
  std::printf("rolled %.4f mm (closed form %.4f mm), v = %.2e m/s\n", 1e3 * distance,
              1e3 * expected, std::hypot(p.vx[0], p.vz[0]));
  EXPECT_NEAR(distance, expected, 0.01 * expected);
  EXPECT_LT(std::hypot(p.vx[0], p.vz[0]), 1e-3 * v0);
  EXPECT_NEAR(std::atan2(p.z[0] - 0.5, p.x[0] - 0.02), a, 1e-6);
}

namespace {

// 400 spheres of s dropped from the random lattice (random depths) into its slab, 3 diameters
// deep: they settle between all six walls, touching across the depth, with the state hash the
// same bits on one and two threads.
void expect_slab_settles(Settings s) {
  auto run = [&](int threads) {
    s.threads = threads;
    DemSolver dem(dem_params_for(s), place_particles(s));
    const auto steps = static_cast<std::int64_t>(0.45 / s.time.dt);
    for (std::int64_t k = 0; k < steps; ++k) dem.step();
    return dem;
  };
  const DemSolver one = run(1);
  const DemSolver two = run(2);
  EXPECT_EQ(one.state_hash(), two.state_hash());
  const Particles& p = one.particles();
  ASSERT_TRUE(p.has_depth());
  double z_lo = 1.0, z_hi = 0.0, top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    z_lo = std::min(z_lo, p.z[i]);
    z_hi = std::max(z_hi, p.z[i]);
    top = std::max(top, p.y[i]);
  }
  const double r = 0.002;
  // Every sphere within the slab (a walls' overlap below 1 % of a radius).
  EXPECT_GT(z_lo, r * 0.99);
  EXPECT_LT(z_hi, 0.012 - r * 0.99);
  // Settled: 400 spheres (1.34e-5 m^3) at a solid fraction of 0.5 to 0.65 fill 0.06 x 0.012 m
  // to 2.9-3.7 cm: the top centre a radius or so below.
  std::printf("settled: top centre %.4f m, z from %.4f to %.4f m, %d pair and %d wall contacts, "
              "KE %.2e J\n",
              top, z_lo, z_hi, one.diagnostics().pair_contacts, one.diagnostics().wall_contacts,
              one.diagnostics().kinetic_energy);
  EXPECT_GT(top, 0.024);
  EXPECT_LT(top, 0.04);
  EXPECT_LT(one.diagnostics().kinetic_energy, 1e-5);
  EXPECT_GT(one.diagnostics().wall_contacts, 100);  // front and back walls carry spheres
}

}  // namespace

TEST(ThickSlab, PackedSlabSettlesInsideItsWallsTheSameOnOneAndTwoThreads) {
  expect_slab_settles(thick_bed(400, 0.06, 0.012, 3));
}

TEST(ThickSlab, HertzMindlinSlabSettlesInsideItsWallsTheSameOnOneAndTwoThreads) {
  // The same with the peer's law for van Wachem's bed (Lethe: E 1e7 Pa, nu 0.3, e 0.9, rolling
  // resistance 0.025) on the paper's spheres.
  Settings s = thick_bed(400, 0.06, 0.012, 3);
  s.contact.law = ContactLaw::HertzMindlin;
  s.contact.youngs_modulus = 1.0e7;
  s.contact.poisson_ratio = 0.3;
  s.contact.restitution = 0.9;
  s.contact.rolling_friction = 0.025;
  expect_slab_settles(s);
}

TEST(ThickSlab, StateFileRestartsTheSameBits) {
  // A thick slab's state file (version 3: z, its velocity, the spin about x and y, the shear
  // vectors of pairs and walls) restarts a run where it stopped: the same hash as the run that
  // went on, mid-way through the settling when every kind of contact history is alive.
  const Settings s = thick_bed(300, 0.05, 0.01, 5);
  DemSolver straight(dem_params_for(s), place_particles(s));
  const auto half = static_cast<std::int64_t>(0.2 / s.time.dt);
  for (std::int64_t k = 0; k < half; ++k) straight.step();
  ASSERT_GT(straight.diagnostics().pair_contacts, 100);
  std::stringstream file;
  write_state(file, straight.exported_state());
  DemState loaded = read_state(file, "memory");
  ASSERT_TRUE(loaded.particles.has_depth());
  ASSERT_FALSE(loaded.pairs.ds_z.empty());
  DemSolver resumed(dem_params_for(s), loaded.particles);
  resumed.set_state(std::move(loaded));
  EXPECT_EQ(resumed.state_hash(), straight.state_hash());
  for (std::int64_t k = 0; k < 2000; ++k) {
    straight.step();
    resumed.step();
  }
  EXPECT_EQ(resumed.state_hash(), straight.state_hash());
}

TEST(ThickSlab, VanWachemsBedExportsToOpenfoamWithEachSpheresDepth) {
  // DPMFoam's mesh starts at the particles' floor: van Wachem's bed as shipped (a plenum under
  // the floor) is refused in one line that names the setting, before anything is written.
  const std::string file = std::string(FLUIDBED_ASSET_DIR) + "/scenes/van_wachem_2001.toml";
  const auto dir = temp_dir("thick-openfoam");
  try {
    write_openfoam_case(load_scene(file), (dir / "case").string(), {});
    FAIL() << "a scene with a plenum was exported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inlet.plenum_height"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "case"));
  // Without it (the gas entering at the floor), the 5-sphere-deep bed is written with depth.
  const Settings s = load_scene(file, {"inlet.plenum_height=0", "gas.cells_y=100",
                                       "particles.placement=lattice", "diagnostics.probes=[]"});
  const OpenfoamCase c = write_openfoam_case(s, (dir / "case").string(), {});
  EXPECT_EQ(c.particles, 17562u);
  const std::string mesh = read_file(dir / "case/system/blockMeshDict");
  EXPECT_NE(mesh.find("(18 100 1)"), std::string::npos);
  EXPECT_EQ(mesh.find("type empty;"), std::string::npos);
  const std::string positions = read_file(dir / "case/constant/kinematicCloudPositions");
  const Particles start = place_particles(s);
  std::size_t off_mid = 0;
  for (std::size_t i = 0; i < start.size(); ++i) off_mid += start.z[i] != 0.004;
  EXPECT_GT(off_mid, start.size() / 2);  // the lattice fills the depth, and the case has it
  std::ostringstream first;
  first << "(" << shortest_number(start.x[0]) << ' ' << shortest_number(start.y[0]) << ' '
        << shortest_number(start.z[0]) << ")";
  EXPECT_NE(positions.find(first.str()), std::string::npos) << first.str();
}
