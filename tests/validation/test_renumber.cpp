// The particles' renumbering by cell (dem/renumber.cpp): it moves particles in memory, never in
// the bed. A renumbered run follows the same trajectories to rounding, names every particle by
// its id, and keeps its determinism: the same bits for any skin (here), on one and two threads
// and after a resume (test_determinism.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "../test_support.hpp"
#include "core/errors.hpp"
#include "run/bubble_recorder.hpp"
#include "scene/scene_loader.hpp"
#include "sim/model_params.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot.hpp"

using namespace fluidbed;

namespace {

// 300 spheres dropped in a narrow box from the lattice.
Settings dropped_bed(int renumber_steps, double thickness = 0.004) {
  Settings s;
  s.scene.kind = SceneKind::Packing;
  s.domain.width = 0.06;
  s.domain.height = 0.2;
  s.domain.thickness = thickness;
  s.particles.count = 300;
  s.particles.seed = 7;
  s.contact.renumber_steps = renumber_steps;
  return s;
}

// The same bed started from a saved state.
Settings started_from(const std::string& path, int renumber_steps, double thickness = 0.004) {
  Settings s = dropped_bed(renumber_steps, thickness);
  s.particles.placement = Placement::State;
  s.particles.state_file = path;
  return s;
}

void run_steps(Simulation& sim, int n) {
  for (int k = 0; k < n; ++k) sim.step();
}

// Largest difference of position (m) between two runs' particles of the same id.
double largest_gap(const Simulation& a, const Simulation& b) {
  const DemState sa = a.dem().exported_state(), sb = b.dem().exported_state();
  const Particles &p = sa.particles, &q = sb.particles;
  double gap = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    double d2 = (p.x[i] - q.x[i]) * (p.x[i] - q.x[i]) + (p.y[i] - q.y[i]) * (p.y[i] - q.y[i]);
    if (p.has_depth()) d2 += (p.z[i] - q.z[i]) * (p.z[i] - q.z[i]);
    gap = std::max(gap, std::sqrt(d2));
  }
  return gap;
}

bool is_identity(const std::vector<std::int32_t>& ids) {
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (ids[k] != static_cast<std::int32_t>(k)) return false;
  return true;
}

// A packed bed (dropped, 20,000 steps) started twice from its state file, renumbered at once
// (its first step) or never: after 200 steps, the same contacts with the same history and the
// same positions by id, to rounding. (A packed bed, because a falling one is chaotic: there the
// two runs part by millimetres within 2,000 steps of the first difference in the last bit.)
void expect_same_trajectories(double thickness, const std::string& name) {
  Simulation packing(dropped_bed(0, thickness));
  run_steps(packing, 20000);
  const auto dir = fluidbed::testing::temp_dir("renumber-" + name);
  const std::string path = (dir / "packed.state").string();
  packing.save_state(path);
  Simulation plain(started_from(path, 0, thickness)), sorted(started_from(path, 100, thickness));
  run_steps(plain, 200);
  run_steps(sorted, 200);
  ASSERT_FALSE(plain.dem().renumbered());
  ASSERT_TRUE(sorted.dem().renumbered());
  EXPECT_FALSE(is_identity(sorted.dem().ids()));
  const DemState a = plain.dem().exported_state(), b = sorted.dem().exported_state();
  ASSERT_GT(a.pairs.size(), 300u);  // packed: the history was carried over
  ASSERT_EQ(a.pairs.i, b.pairs.i);
  ASSERT_EQ(a.pairs.j, b.pairs.j);
  // The runs differ by the order of the sums over each particle's contacts: rounding. A history
  // carried with the wrong sign reverses its tangential spring: ds differs by its own size.
  double ds_scale = 0.0, ds_gap = 0.0;
  for (std::size_t k = 0; k < a.pairs.size(); ++k) {
    auto shear = [&](const DemState& s, std::size_t q) {
      return std::array<double, 3>{s.pairs.ds[q], s.pairs.ds_y.empty() ? 0.0 : s.pairs.ds_y[q],
                                   s.pairs.ds_z.empty() ? 0.0 : s.pairs.ds_z[q]};
    };
    const auto u = shear(a, k), v = shear(b, k);
    for (int c = 0; c < 3; ++c) {
      ds_scale = std::max(ds_scale, std::fabs(u[c]));
      ds_gap = std::max(ds_gap, std::fabs(u[c] - v[c]));
    }
  }
  EXPECT_GT(ds_scale, 1e-9);
  EXPECT_LT(ds_gap, 1e-9 * ds_scale) << name;
  EXPECT_LT(largest_gap(plain, sorted), 1e-12) << name;  // m: 4 mm spheres
  // The mixing index pairs each particle's height at the start with where it is now.
  BubbleRecorder mix_plain(plain), mix_sorted(sorted);
  mix_plain.analyse(plain);
  mix_sorted.analyse(sorted);
  EXPECT_TRUE(mix_plain.mixing_summary()["lacey_index_final"].is_number());
  EXPECT_EQ(mix_plain.mixing_summary().dump(), mix_sorted.mixing_summary().dump()) << name;
}

}  // namespace

TEST(Renumber, RenumberedMonolayerFollowsTheSameTrajectoriesToRounding) {
  expect_same_trajectories(0.004, "monolayer");
}

TEST(Renumber, RenumberedThickSlabFollowsTheSameTrajectoriesToRounding) {
  expect_same_trajectories(0.012, "slab");
}

TEST(Renumber, RenumberedFluidizedSlabFollowsTheSameTrajectoriesToRounding) {
  // The coupler's per-particle data follows the particles: van Wachem's model in small (a thick
  // slab, rolling resistance, the gas every 10 steps) started from a packed bed with the gas on,
  // renumbered every 55 steps (mid-way through the gas's cycle) or never.
  Settings s = dropped_bed(0, 0.012);
  s.contact.rolling_friction = 0.025;
  Simulation packing(s);
  run_steps(packing, 20000);
  const auto dir = fluidbed::testing::temp_dir("renumber-gas");
  const std::string path = (dir / "packed.state").string();
  packing.save_state(path);
  auto fluidized = [&](int renumber_steps) {
    Settings g = started_from(path, renumber_steps, 0.012);
    g.contact.rolling_friction = 0.025;
    g.gas.enabled = true;
    g.gas.cells_x = 6;
    g.gas.cells_y = 20;
    g.inlet.superficial_velocity = 2.5;
    g.coupling.particle_steps_per_gas_step = 10;
    return g;
  };
  Simulation plain(fluidized(0)), sorted(fluidized(55));
  run_steps(plain, 300);
  run_steps(sorted, 300);
  ASSERT_TRUE(sorted.dem().renumbered());
  EXPECT_FALSE(is_identity(sorted.dem().ids()));
  EXPECT_GT(plain.dem().diagnostics().pair_contacts, 300);
  // Moving: the gas lifts the bed (a drag given to the wrong sphere moves it by millimetres).
  EXPECT_GT(largest_gap(plain, packing), 1e-5);
  EXPECT_LT(largest_gap(plain, sorted), 1e-12);
}

TEST(Renumber, SameBitsForAnySkin) {
  // The schedule counts steps and the sort's cells are a diameter: the neighbour list's rebuild
  // times (set by the skin) change no bit.
  Settings s = dropped_bed(500);
  s.contact.skin = 0.2;
  Simulation thin(s);
  s.contact.skin = 0.8;
  Simulation wide(s);
  run_steps(thin, 6000);
  run_steps(wide, 6000);
  EXPECT_TRUE(thin.dem().renumbered());
  EXPECT_NE(thin.dem().neighbours().builds(), wide.dem().neighbours().builds());
  EXPECT_EQ(thin.state_hash(), wide.state_hash());
}

TEST(Renumber, PicturesAndTracksNameParticlesByTheirIds) {
  Simulation sim(dropped_bed(2000));
  const std::vector<double> start = sim.initial_heights();
  run_steps(sim, 4001);
  ASSERT_TRUE(sim.dem().renumbered());
  const DemSolver& dem = sim.dem();
  const DemState by_id = dem.exported_state();
  Snapshot snap;
  take_snapshot(sim, snap);
  ASSERT_EQ(snap.particles(), by_id.particles.size());
  for (std::size_t id = 0; id < snap.particles(); ++id) {
    const std::size_t at = dem.place_of(id);
    ASSERT_EQ(dem.id_of(at), id);
    ASSERT_EQ(snap.x[id], by_id.particles.x[id]);
    ASSERT_EQ(snap.x[id], dem.particles().x[at]);
    ASSERT_EQ(snap.fy[id], dem.particles().fy[at]);
    ASSERT_EQ(snap.overlap[id], dem.particle_overlap()[at]);
  }
  EXPECT_EQ(snap.initial_y, start);
}

TEST(Renumber, StateFileKeepsItsIdsAndRefusesABrokenOrder) {
  Simulation sim(dropped_bed(2000));
  run_steps(sim, 4001);
  DemState st = sim.dem().exported_state();
  ASSERT_FALSE(st.order.empty());
  const auto dir = fluidbed::testing::temp_dir("renumber-state");
  const std::string path = (dir / "s.state").string();
  save_state_file(path, st);
  const DemState back = load_state_file(path);
  EXPECT_EQ(back.order, st.order);
  EXPECT_EQ(back.particles.x, st.particles.x);
  EXPECT_EQ(back.pairs.ds, st.pairs.ds);
  // A scene started from it keeps the order, and its particles' heights at the start by id.
  Simulation started(started_from(path, 2000));
  EXPECT_EQ(started.dem().ids(), st.order);
  EXPECT_EQ(started.initial_heights(), st.particles.y);
  EXPECT_EQ(started.dem().configuration_hash(), sim.dem().configuration_hash());
  // A particle named twice in the order is refused in words.
  st.order[1] = st.order[0];
  Simulation other(dropped_bed(2000));
  try {
    other.dem().set_state(st);
    FAIL() << "a broken order was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a permutation"), std::string::npos) << e.what();
  }
}

TEST(Renumber, AutomaticInBedsWhoseArraysLeaveTheCache) {
  Particles p;
  p.resize(3);
  EXPECT_EQ(p.all_arrays().size() * sizeof(double), Particles::bytes_per_particle(false));
  p.add_depth(0.002);
  EXPECT_EQ(p.all_arrays().size() * sizeof(double), Particles::bytes_per_particle(true));
  const std::string scenes = std::string(FLUIDBED_ASSET_DIR) + "/scenes/";
  // The paper's bed (0.33 MB of arrays) and the teaching bed keep their order; van Wachem's (a
  // thick slab, 3.9 MB) and the wide bed (3.3 MB) would be renumbered; the key overrides (van
  // Wachem's scene keeps its validated order).
  EXPECT_EQ(dem_params_for(load_scene(scenes + "xu_yu_1997.toml")).renumber_steps, 0);
  EXPECT_EQ(dem_params_for(load_scene(scenes + "teaching.toml")).renumber_steps, 0);
  const std::string van_wachem = scenes + "van_wachem_2001.toml";
  EXPECT_EQ(dem_params_for(load_scene(van_wachem, {"contact.renumber_steps=-1"})).renumber_steps,
            kAutoRenumberSteps);
  EXPECT_EQ(dem_params_for(load_scene(van_wachem)).renumber_steps, 0);
  EXPECT_EQ(dem_params_for(load_scene(scenes + "wide.toml")).renumber_steps, kAutoRenumberSteps);
  EXPECT_EQ(dem_params_for(load_scene(scenes + "wide.toml", {"contact.renumber_steps=0"}))
                .renumber_steps,
            0);
  EXPECT_EQ(dem_params_for(load_scene(scenes + "xu_yu_1997.toml", {"contact.renumber_steps=50"}))
                .renumber_steps,
            50);
  for (const char* bad : {"contact.renumber_steps=-2", "contact.renumber_steps=1.5"})
    EXPECT_THROW(load_scene(scenes + "xu_yu_1997.toml", {bad}), InputError) << bad;
}
