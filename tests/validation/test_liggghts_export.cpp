// `fluidbed export --to liggghts`: the deck and data file hold the scene's numbers (read back
// here), and, where Debian's LIGGGHTS 3.8 is installed (apt-get install liggghts), the exported
// cases run in it: a short packing, a wall drop whose restitution shows the absolute damping was
// taken as absolute, and the full 0.8 s packing against fluidbed's settled bed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>

#include "../liggghts_support.hpp"
#include "../test_support.hpp"
#include "core/errors.hpp"
#include "analysis/mechanical_energy.hpp"
#include "analysis/packing_metrics.hpp"
#include "io/liggghts_export.hpp"
#include "scene/scene_loader.hpp"
#include "sim/placement.hpp"
#include "run/run_loop.hpp"
#include "sim/simulation.hpp"

using namespace fluidbed;
using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

Settings packing_scene(const std::vector<std::string>& overrides = {}) {
  return load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/packing.toml", overrides);
}

// The deck as commands: comments dropped, `&` continuations joined, split into words.
using Command = std::vector<std::string>;
std::vector<Command> read_deck(const fs::path& path) {
  std::vector<Command> commands;
  std::istringstream in(read_file(path));
  std::string pending;
  for (std::string line; std::getline(in, line);) {
    // '#' starts a comment except inside quotes (the dump's format string has none).
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const auto amp = line.find_last_not_of(" \t");
    if (amp != std::string::npos && line[amp] == '&') {
      pending += line.substr(0, amp) + ' ';
      continue;
    }
    std::istringstream words(pending + line);
    pending.clear();
    Command c;
    for (std::string w; words >> w;) c.push_back(w);
    if (!c.empty()) commands.push_back(c);
  }
  return commands;
}

// Commands whose first word is `first`; for "fix", those of one style (fix ID group STYLE ...).
std::vector<Command> find_all(const std::vector<Command>& deck, const std::string& first,
                              const std::string& style = "") {
  std::vector<Command> r;
  for (const Command& c : deck)
    if (c[0] == first && (style.empty() || (c.size() > 3 && c[3] == style))) r.push_back(c);
  return r;
}

std::string joined(const Command& c) {
  std::string s;
  for (const auto& w : c) s += (s.empty() ? "" : " ") + w;
  return s;
}

// fix ID all property/global NAME peratomtypepair 1 VALUE, in deck order.
std::vector<std::pair<std::string, double>> law_values(const std::vector<Command>& deck) {
  std::vector<std::pair<std::string, double>> v;
  for (const Command& c : find_all(deck, "fix", "property/global")) {
    EXPECT_EQ(c.size(), 8u) << joined(c);
    if (c.size() != 8) continue;
    EXPECT_EQ(c[5], "peratomtypepair");
    EXPECT_EQ(c[6], "1");
    v.emplace_back(c[4], std::stod(c[7]));
  }
  return v;
}

// Walls as (axis, position), e.g. ("xplane", 0.15).
std::vector<std::pair<std::string, double>> walls(const std::vector<Command>& deck) {
  std::vector<std::pair<std::string, double>> w;
  for (const Command& c : find_all(deck, "fix", "wall/gran")) {
    EXPECT_NE(joined(c).find("wall/gran model hooke/stiffness tangential history primitive type 1"),
              std::string::npos)
        << joined(c);
    EXPECT_EQ(c.back(), "on");
    EXPECT_EQ(c[c.size() - 2], "absolute_damping");
    w.emplace_back(c[c.size() - 4], std::stod(c[c.size() - 3]));
  }
  return w;
}

std::vector<std::int64_t> run_lengths(const std::vector<Command>& deck) {
  std::vector<std::int64_t> n;
  for (const Command& c : find_all(deck, "run")) n.push_back(std::stoll(c.at(1)));
  return n;
}

// The data file read back: header counts, box, atoms and velocities by id.
struct DataFile {
  long atoms = -1;
  int types = -1;
  std::map<std::string, std::pair<double, double>> box;  // "x" -> (lo, hi)
  std::vector<std::array<double, 7>> atom;               // id type diameter density x y z
  std::vector<std::array<double, 7>> velocity;           // id vx vy vz wx wy wz
};

DataFile read_data(const fs::path& path) {
  DataFile d;
  std::istringstream in(read_file(path));
  std::string line;
  std::getline(in, line);  // title
  std::vector<std::array<double, 7>>* section = nullptr;
  while (std::getline(in, line)) {
    std::istringstream w(line);
    std::vector<std::string> t;
    for (std::string s; w >> s;) t.push_back(s);
    if (t.empty()) continue;
    if (t.size() == 2 && t[1] == "atoms")
      d.atoms = std::stol(t[0]);
    else if (t.size() == 3 && t[1] == "atom" && t[2] == "types")
      d.types = std::stoi(t[0]);
    else if (t.size() == 4 && t[3].size() == 3 && t[3].substr(1) == "hi")
      d.box[t[2].substr(0, 1)] = {std::stod(t[0]), std::stod(t[1])};
    else if (t[0] == "Atoms")
      section = &d.atom;
    else if (t[0] == "Velocities")
      section = &d.velocity;
    else if (section) {
      EXPECT_EQ(t.size(), 7u) << line;
      std::array<double, 7> row{};
      for (std::size_t k = 0; k < 7 && k < t.size(); ++k) row[k] = std::stod(t[k]);
      section->push_back(row);
    }
  }
  return d;
}


}  // namespace

TEST(LiggghtsExport, DeckAndDataHoldTheScenesNumbers) {
  const Settings s = packing_scene();
  const fs::path dir = temp_dir("liggghts-packing");
  const LiggghtsCase c = write_liggghts_case(s, dir.string());
  EXPECT_EQ(fs::path(c.deck), dir / "in.liggghts");
  EXPECT_EQ(fs::path(c.data), dir / "particles.data");
  const auto deck = read_deck(c.deck);

  // The contact law: kn = kt = 5e4 N/m, absolute damping 0.15 kg/s, friction 0.3.
  const auto law = law_values(deck);
  const std::vector<std::pair<std::string, double>> want = {{"kn", 5e4},
                                                            {"kt", 5e4},
                                                            {"gamman_abs", 0.15},
                                                            {"gammat_abs", 0.15},
                                                            {"coefficientFriction", 0.3}};
  EXPECT_EQ(law, want);
  const auto pair = find_all(deck, "pair_style");
  ASSERT_EQ(pair.size(), 1u);
  EXPECT_EQ(joined(pair[0]),
            "pair_style gran model hooke/stiffness tangential history "
            "absolute_damping on");
  ASSERT_EQ(find_all(deck, "timestep").size(), 1u);
  EXPECT_EQ(std::stod(find_all(deck, "timestep")[0][1]), s.time.dt);
  const auto gravity = find_all(deck, "fix", "gravity");
  ASSERT_EQ(gravity.size(), 1u);
  EXPECT_EQ(joined(gravity[0]), "fix gravity all gravity 9.81 vector 0.0 -1.0 0.0");
  EXPECT_EQ(find_all(deck, "fix", "nve/sphere").size(), 1u);

  // Left, right, bottom; no top (packing.toml is open), no front and back: z is held instead.
  const std::vector<std::pair<std::string, double>> planes = {
      {"xplane", 0.0}, {"xplane", 0.15}, {"yplane", 0.0}};
  EXPECT_EQ(walls(deck), planes);
  const auto planar = find_all(deck, "fix", "setforce");
  ASSERT_EQ(planar.size(), 1u);
  EXPECT_EQ(joined(planar[0]), "fix planar all setforce NULL NULL 0.0");

  // time.end = 0.8 s at 1.5e-5 s: 53333 steps, as fluidbed counts them (llround).
  EXPECT_EQ(run_lengths(deck), std::vector<std::int64_t>{53333});
  ASSERT_EQ(find_all(deck, "thermo_style").size(), 1u);
  EXPECT_NE(joined(find_all(deck, "thermo_style")[0]).find(" ke "), std::string::npos);
  ASSERT_EQ(find_all(deck, "write_dump").size(), 1u);
  const std::string text = read_file(c.deck);
  EXPECT_NE(text.find("the gas is left out"), std::string::npos);
  ASSERT_FALSE(c.notes.empty());
  EXPECT_NE(c.notes[0].find("gas is left out"), std::string::npos);

  // The data file: the same 2400 spheres, bit for bit, on the slab's mid-plane.
  const DataFile d = read_data(c.data);
  const Particles p = place_particles(s);
  EXPECT_EQ(d.atoms, 2400);
  EXPECT_EQ(d.types, 1);
  EXPECT_EQ(d.box.at("x"), std::make_pair(0.0, 0.15));
  EXPECT_EQ(d.box.at("y"), std::make_pair(0.0, 0.9 + 0.002));
  EXPECT_EQ(d.box.at("z"), std::make_pair(0.0, 0.004));
  ASSERT_EQ(d.atom.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& a = d.atom[i];
    ASSERT_EQ(a[0], static_cast<double>(i + 1));
    ASSERT_EQ(a[1], 1.0);
    ASSERT_EQ(a[2], 0.004);
    ASSERT_EQ(a[3], 2700.0);
    ASSERT_EQ(a[4], p.x[i]) << "atom " << i + 1;
    ASSERT_EQ(a[5], p.y[i]) << "atom " << i + 1;
    ASSERT_EQ(a[6], 0.002);
  }
  EXPECT_TRUE(d.velocity.empty());  // the lattice start is at rest
}

TEST(LiggghtsExport, TopWallAndTheSixWallVariant) {
  Settings s = packing_scene({"domain.top_wall=true"});
  const fs::path dir = temp_dir("liggghts-walls");
  write_liggghts_case(s, (dir / "top").string());
  const std::vector<std::pair<std::string, double>> top = {
      {"xplane", 0.0}, {"xplane", 0.15}, {"yplane", 0.0}, {"yplane", 0.9}};
  EXPECT_EQ(walls(read_deck(dir / "top" / "in.liggghts")), top);
  EXPECT_EQ(read_data(dir / "top" / "particles.data").box.at("y"), std::make_pair(0.0, 0.9));

  LiggghtsExportOptions six;
  six.front_back_walls = true;
  write_liggghts_case(packing_scene(), (dir / "six").string(), six);
  const auto deck = read_deck(dir / "six" / "in.liggghts");
  const std::vector<std::pair<std::string, double>> slab = {
      {"xplane", 0.0}, {"xplane", 0.15}, {"yplane", 0.0}, {"zplane", 0.0}, {"zplane", 0.004}};
  EXPECT_EQ(walls(deck), slab);
  EXPECT_TRUE(find_all(deck, "fix", "setforce").empty());
}

TEST(LiggghtsExport, RollingFrictionIsLiggghtsConstantDirectionalTorque) {
  // contact.rolling_friction = 0.05: the rolling_friction cdt model on the pair style and every
  // wall, with its coefficient among the law's values; without it (the default) none of that.
  const fs::path dir = temp_dir("liggghts-rolling");
  const auto deck = read_deck(
      write_liggghts_case(packing_scene({"contact.rolling_friction=0.05"}), dir.string()).deck);
  const auto law = law_values(deck);
  ASSERT_EQ(law.size(), 6u);
  EXPECT_EQ(law.back(), std::make_pair(std::string("coefficientRollingFriction"), 0.05));
  const std::string model = "model hooke/stiffness tangential history rolling_friction cdt";
  ASSERT_EQ(find_all(deck, "pair_style").size(), 1u);
  EXPECT_NE(joined(find_all(deck, "pair_style")[0]).find(model), std::string::npos);
  for (const auto& wall : find_all(deck, "fix", "wall/gran"))
    EXPECT_NE(joined(wall).find(model), std::string::npos) << joined(wall);
  const auto plain = read_deck(
      write_liggghts_case(packing_scene(), (dir / "plain").string()).deck);
  EXPECT_EQ(law_values(plain).size(), 5u);
  EXPECT_EQ(joined(find_all(plain, "pair_style")[0]).find("rolling"), std::string::npos);
}

TEST(LiggghtsExport, SingleParticleKeepsItsVelocityAndSpin) {
  Settings s = single_particle(0.05, 0.1, 0.3, -0.2);
  s.particles.spin = 12.0;
  s.contact.stiffness = 2e4;
  s.contact.tangential_stiffness_ratio = 0.5;
  s.contact.damping = 0.1;
  s.contact.tangential_damping_ratio = 0.25;
  s.contact.friction = 0.4;
  s.time.integrator = Integrator::VelocityVerlet;
  s.time.end = 0.25;
  const fs::path dir = temp_dir("liggghts-single");
  const LiggghtsCase c = write_liggghts_case(s, dir.string());
  const auto deck = read_deck(c.deck);
  const std::vector<std::pair<std::string, double>> want = {{"kn", 2e4},
                                                            {"kt", 1e4},
                                                            {"gamman_abs", 0.1},
                                                            {"gammat_abs", 0.025},
                                                            {"coefficientFriction", 0.4}};
  EXPECT_EQ(law_values(deck), want);
  EXPECT_EQ(run_lengths(deck), std::vector<std::int64_t>{std::llround(0.25 / 1.5e-5)});
  // No gas in this scene: nothing about it in the notes.
  for (const auto& n : c.notes) EXPECT_EQ(n.find("gas"), std::string::npos) << n;
  const DataFile d = read_data(c.data);
  ASSERT_EQ(d.atom.size(), 1u);
  EXPECT_EQ(d.atom[0][4], 0.05);
  EXPECT_EQ(d.atom[0][5], 0.1);
  ASSERT_EQ(d.velocity.size(), 1u);
  const std::array<double, 7> v = {1.0, 0.3, -0.2, 0.0, 0.0, 0.0, 12.0};
  EXPECT_EQ(d.velocity[0], v);
}

TEST(LiggghtsExport, PackedStartRunsThePackingFirstWithThePackingScenesLaw) {
  // ideal.toml: no damping, no friction, packed as xu_yu_1997.toml packs (damped, frictional).
  const Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/ideal.toml");
  const fs::path dir = temp_dir("liggghts-ideal");
  const LiggghtsCase c = write_liggghts_case(s, dir.string());
  const auto deck = read_deck(c.deck);
  EXPECT_EQ(run_lengths(deck),
            (std::vector<std::int64_t>{std::llround(0.8 / 1.5e-5), std::llround(6.0 / 1.5e-5)}));
  const std::vector<std::pair<std::string, double>> want = {{"kn", 5e4},
                                                            {"kt", 5e4},
                                                            {"gamman_abs", 0.15},
                                                            {"gammat_abs", 0.15},
                                                            {"coefficientFriction", 0.3},
                                                            {"kn", 5e4},
                                                            {"kt", 5e4},
                                                            {"gamman_abs", 0.0},
                                                            {"gammat_abs", 0.0},
                                                            {"coefficientFriction", 0.0}};
  EXPECT_EQ(law_values(deck), want);
  EXPECT_EQ(find_all(deck, "reset_timestep").size(), 1u);
  // The start is the lattice the packing starts from.
  Settings lattice = s;
  lattice.particles.placement = Placement::Lattice;
  const Particles p = place_particles(lattice);
  const DataFile d = read_data(c.data);
  ASSERT_EQ(d.atom.size(), p.size());
  EXPECT_EQ(d.atom.back()[4], p.x.back());
  EXPECT_EQ(d.atom.back()[5], p.y.back());
  EXPECT_NE(read_file(c.deck).find("U = 2.8 m/s"), std::string::npos);  // the jet left out
}

TEST(LiggghtsExport, PackingFrictionIsThePackingStagesLaw) {
  // Lethe's loading: packed with rolling friction 0.2, then run with the scene's 0.025.
  const fs::path dir = temp_dir("liggghts-packing-friction");
  const LiggghtsCase c = write_liggghts_case(
      packing_scene({"particles.placement=packed", "contact.rolling_friction=0.025",
                     "particles.packing_rolling_friction=0.2"}),
      dir.string());
  const std::string deck = read_file(c.deck);
  const auto packing = deck.find("coefficientRollingFriction peratomtypepair 1 0.2\n");
  const auto bed = deck.find("coefficientRollingFriction peratomtypepair 1 0.025\n");
  ASSERT_NE(packing, std::string::npos) << deck;
  ASSERT_NE(bed, std::string::npos) << deck;
  EXPECT_LT(packing, bed);
}

TEST(LiggghtsExport, StateStartWritesTheSavedPositionsAndVelocities) {
  const fs::path dir = temp_dir("liggghts-state");
  Settings s = single_particle(0.075, 0.0025, 0.1, -0.3);
  Simulation sim(s);
  for (int k = 0; k < 200; ++k) sim.step();  // into a wall contact, with history
  sim.save_state((dir / "drop.state").string());
  Settings t = s;
  t.particles.placement = Placement::State;
  t.particles.state_file = "drop.state";
  t.source_dir = dir.string();
  const LiggghtsCase c = write_liggghts_case(t, (dir / "case").string());
  const Particles& p = sim.dem().particles();
  const DataFile d = read_data(c.data);
  ASSERT_EQ(d.atom.size(), 1u);
  ASSERT_EQ(d.velocity.size(), 1u);
  EXPECT_EQ(d.atom[0][4], p.x[0]);
  EXPECT_EQ(d.atom[0][5], p.y[0]);
  EXPECT_EQ(d.velocity[0][1], p.vx[0]);
  EXPECT_EQ(d.velocity[0][2], p.vy[0]);
  EXPECT_EQ(d.velocity[0][6], p.w[0]);
  bool said = false;
  for (const auto& n : c.notes) said = said || n.find("contact history") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(LiggghtsExport, RefusesWhatTheDeckCannotExpress) {
  const fs::path dir = temp_dir("liggghts-refused");
  EXPECT_THROW(write_liggghts_case(packing_scene({"time.integrator=symplectic_euler"}),
                                   (dir / "euler").string()),
               InputError);
  EXPECT_THROW(
      write_liggghts_case(packing_scene({"particles.frozen=true"}), (dir / "frozen").string()),
      InputError);
  Settings missing =
      packing_scene({"particles.placement=state", "particles.state_file=no-such.state"});
  EXPECT_THROW(write_liggghts_case(missing, (dir / "missing").string()), InputError);
  // Walls with their own friction: the deck's walls take the particles' law (one atom type).
  EXPECT_THROW(write_liggghts_case(packing_scene({"contact.wall_friction=0.1"}),
                                   (dir / "walls").string()),
               InputError);
  EXPECT_FALSE(fs::exists(dir / "walls"));
  // A refusal writes nothing.
  EXPECT_FALSE(fs::exists(dir / "euler"));
  EXPECT_FALSE(fs::exists(dir / "frozen"));
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

TEST(LiggghtsExport, DumpReaderTakesTheLastSnapshotInIdOrder) {
  const fs::path dir = temp_dir("liggghts-dump");
  write_file(dir / "two.dump",
             "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n"
             "0 1\nITEM: ATOMS id type radius x y z\n1 1 0.002 0.1 0.2 0.002\n"
             "2 1 0.002 0.3 0.4 0.002\n"
             "ITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n"
             "0 1\nITEM: ATOMS x y id radius\n0.7 0.8 2 0.003\n0.5 0.6 1 0.002\n");
  const Particles p = read_liggghts_dump((dir / "two.dump").string(), 2700.0);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p.x[0], 0.5);
  EXPECT_EQ(p.y[0], 0.6);
  EXPECT_EQ(p.x[1], 0.7);
  EXPECT_EQ(p.y[1], 0.8);
  EXPECT_EQ(p.radius[1], 0.003);
  EXPECT_NEAR(p.mass[0], paper_mass(), 1e-18);
  write_file(dir / "bad.dump", "ITEM: NUMBER OF ATOMS\n1\nITEM: ATOMS id x y\n1 0.1 0.2\n");
  EXPECT_THROW(read_liggghts_dump((dir / "bad.dump").string(), 2700.0), InputError);
  EXPECT_THROW(read_liggghts_dump((dir / "none.dump").string(), 2700.0), InputError);
}

// The exported packing runs in LIGGGHTS: 300 steps of free fall from the lattice start.
TEST(LiggghtsRun, ExportedPackingRunsAFewHundredSteps) {
  REQUIRE_LIGGGHTS(binary);
  const Settings s = packing_scene({"time.end=0.0045"});  // 300 steps
  const fs::path dir = temp_dir("liggghts-run-short");
  write_liggghts_case(s, dir.string());
  const LiggghtsRun r = run_liggghts(*binary, dir);
  ASSERT_EQ(r.status, 0) << r.log;
  EXPECT_EQ(r.log.find("ERROR"), std::string::npos) << r.log;
  const Particles start = place_particles(s);
  const Particles end = read_liggghts_dump((dir / "final.dump").string(), s.particles.density);
  ASSERT_EQ(end.size(), start.size());
  // The bottom row rests on the floor (sunk by m g / kn = 18 nm); every other sphere has not
  // landed yet and fell g t^2 / 2 (velocity Verlet is exact for it).
  const double t = 300 * s.time.dt, fall = 0.5 * 9.81 * t * t, radius = 0.002;
  int resting = 0;
  for (std::size_t i = 0; i < end.size(); ++i) {
    ASSERT_NEAR(end.x[i], start.x[i], 1e-12) << "sphere " << i + 1;
    const bool on_floor = start.y[i] == radius;
    resting += on_floor;
    ASSERT_NEAR(end.y[i], on_floor ? radius : start.y[i] - fall, on_floor ? 1e-7 : 1e-9)
        << "sphere " << i + 1;
  }
  EXPECT_GT(resting, 0);
  // Thermo: the kinetic energy of 2400 spheres at v = g t, in J (3-d sphere masses).
  const auto rows = thermo_rows(r.log);
  ASSERT_FALSE(rows.empty()) << r.log;
  const auto& row = rows.back();
  EXPECT_EQ(row[0], 300.0);
  EXPECT_EQ(row[1], 2400.0);
  const double ke = 0.5 * (2400 - resting) * paper_mass() * (9.81 * t) * (9.81 * t);
  EXPECT_NEAR(row[2], ke, 1e-3 * ke);
}

// The absolute damping reaches LIGGGHTS as absolute (gamman_abs, kg/s): a sphere dropped on the
// floor keeps e^2 of its energy, e = 0.895 for eta = 0.15 kg/s (scaled by the mass it would be
// almost elastic). Measured from the final dump, after one bounce.
TEST(LiggghtsRun, WallRestitutionIsTheDashpots) {
  REQUIRE_LIGGGHTS(binary);
  const Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/drop.toml",
                                {"time.end=0.15"});  // landed at 0.10 s, apex at 0.19 s
  const fs::path dir = temp_dir("liggghts-run-drop");
  write_liggghts_case(s, dir.string());
  const LiggghtsRun r = run_liggghts(*binary, dir);
  ASSERT_EQ(r.status, 0) << r.log;
  std::istringstream dump(read_file(dir / "final.dump"));
  std::string line, last;
  while (std::getline(dump, line))
    if (!line.empty()) last = line;
  std::istringstream row(last);  // id type radius x y z vx vy vz omegaz
  std::array<double, 10> a{};
  for (double& v : a) row >> v;
  const double g = 9.81, r0 = 0.002;
  const double energy = 0.5 * a[7] * a[7] + g * (a[4] - r0), start = g * (s.particles.y - r0);
  const double e = std::sqrt(energy / start);
  const double want = analytic_restitution(5e4, 0.15, paper_mass());
  std::printf("LIGGGHTS wall restitution %.4f, analytic %.4f\n", e, want);
  EXPECT_GT(a[7], 0.0);  // rising after the bounce
  EXPECT_NEAR(e, want, 0.01 * want);
}

// The full packing (0.8 s, 2400 spheres, about 20-40 s on one core) settles to fluidbed's bed:
// `fluidbed run assets/scenes/packing.toml` gives 0.2345 m and 0.567 (the peers 0.232-0.236 m
// over 5 seeds), measured with the same definitions (packing_metrics.hpp) from the final dump.
TEST(LiggghtsRun, SettledPackingMatchesFluidbeds) {
  REQUIRE_LIGGGHTS(binary);
  const Settings s = packing_scene();
  const fs::path dir = temp_dir("liggghts-run-packing");
  write_liggghts_case(s, dir.string());
  const LiggghtsRun r = run_liggghts(*binary, dir);
  ASSERT_EQ(r.status, 0) << r.log;
  const Particles p = read_liggghts_dump((dir / "final.dump").string(), s.particles.density);
  ASSERT_EQ(p.size(), 2400u);
  const PackingMetrics m = measure_packing(p, s.domain.width, s.domain.thickness);
  const auto rows = thermo_rows(r.log);
  ASSERT_FALSE(rows.empty()) << r.log;
  double peak = 0.0;
  for (const auto& row : rows) peak = std::max(peak, row[4]);
  const double end = rows.back()[4];
  std::printf(
      "LIGGGHTS packing: bed height %.4f m, solid fraction %.4f, KE end / peak %.2e, "
      "%.1f s wall, %.3g particle-steps/s\n",
      m.bed_height, m.solid_fraction, end / peak, r.wall_s, 2400.0 * 53333.0 / r.wall_s);
  EXPECT_NEAR(m.bed_height, 0.2345, 0.03 * 0.2345);
  EXPECT_NEAR(m.solid_fraction, 0.567, 0.03 * 0.567);
  // Settled, by fluidbed's own criterion (test_packing.cpp): the kinetic energy at the end is
  // below a thousandth of its peak (0.36 J as the bed lands).
  EXPECT_EQ(rows.back()[0], 53333.0);
  EXPECT_LT(end, 1e-3 * peak);
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_GE(p.x[i], 0.0);
    ASSERT_LE(p.x[i], s.domain.width);
    ASSERT_GE(p.y[i], 0.0);
  }
}

TEST(LiggghtsRun, ElasticBoxGainsEnergyAsFluidbedsVerletDoes) {
  // The energy study's box (2400 elastic frictionless spheres, no gas, a top wall), agitated by
  // 0.3 s of falling from the lattice, then 0.2 s in fluidbed (velocity Verlet, geometric overlap:
  // LIGGGHTS's scheme) and in LIGGGHTS from the same state. The total mechanical energy (kinetic,
  // spin, m g y, 1/2 kappa delta^2 of the geometric overlaps: analysis/mechanical_energy) taken
  // from the snapshots of both: nothing dissipates, so its change is each code's integration error.
  REQUIRE_LIGGGHTS(binary);
  Settings s;
  s.scene.kind = SceneKind::Packing;
  s.domain.top_wall = true;
  s.contact.damping = 0.0;
  s.contact.friction = 0.0;
  s.particles.fill_height = 0.45;
  s.time.integrator = Integrator::VelocityVerlet;
  s.contact.displacement = Displacement::Geometric;
  const fs::path dir = temp_dir("liggghts-elastic-box");
  {
    Simulation agitate(s);
    RunOptions opt;
    opt.until = 0.3;
    run_simulation(agitate, opt);
    agitate.save_state((dir / "agitated.state").string());
  }
  s.particles.placement = Placement::State;
  s.particles.state_file = (dir / "agitated.state").string();
  s.time.end = 0.2;
  const double g = s.physics.gravity, kn = s.contact.stiffness;
  const double mgd = paper_mass() * g * s.particles.diameter * 2400.0;
  // fluidbed.
  Simulation sim(s);
  const double e0 = mechanical_energy(sim.dem().particles(), sim.dem().walls(), kn, g).total();
  RunOptions opt;
  opt.until = s.time.end;
  run_simulation(sim, opt);
  const double e1 = mechanical_energy(sim.dem().particles(), sim.dem().walls(), kn, g).total();
  const double ours = (e1 - e0) / s.time.end / mgd;
  // LIGGGHTS.
  LiggghtsExportOptions lo;
  lo.frames_every = 0.01;
  write_liggghts_case(s, (dir / "liggghts").string(), lo);
  const LiggghtsRun r = run_liggghts(*binary, dir / "liggghts");
  ASSERT_EQ(r.status, 0) << r.log;
  const auto frames = read_liggghts_frames((dir / "liggghts" / "frames.dump").string(), s.particles.density);
  ASSERT_GE(frames.size(), 2u);
  const auto walls = sim.dem().walls();
  const double l0 = mechanical_energy(frames.front().particles, walls, kn, g).total();
  const double l1 = mechanical_energy(frames.back().particles, walls, kn, g).total();
  const double span = static_cast<double>(frames.back().step - frames.front().step) * s.time.dt;
  const double theirs = (l1 - l0) / span / mgd;
  std::printf("elastic box, velocity Verlet, geometric, dt 1.5e-5 s: energy change per s / (N m g D): "
              "fluidbed %+.3g, LIGGGHTS %+.3g (start %.6g J and %.6g J)\n", ours, theirs, e0, l0);
  // The same start (the data file holds the state's positions and velocities).
  EXPECT_NEAR(l0, e0, 1e-6 * std::fabs(e0));
  // The same scheme's error: both gain, by amounts within a factor of 3 of each other (each is
  // one sample of a chaotic box; the energy study measured +1.4 for fluidbed).
  EXPECT_GT(ours, 0.0);
  EXPECT_GT(theirs, 0.0);
  EXPECT_LT(std::max(ours / theirs, theirs / ours), 3.0);
}
