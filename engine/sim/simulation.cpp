#include "sim/simulation.hpp"

#include "sim/placement.hpp"

namespace fluidbed {
namespace {

DemSolver make_dem(const Settings& s) {
  if (s.particles.placement != "state") return DemSolver(s, place_particles(s));
  // A saved configuration starts a new experiment: its history is kept, its clock restarts.
  DemState st = load_scene_state(s);
  st.time = 0.0;
  st.step = 0;
  Particles p = st.particles;
  DemSolver dem(s, std::move(p));
  dem.set_state(std::move(st));
  return dem;
}

}  // namespace

Simulation::Simulation(const Settings& s) : settings_(s), dem_(make_dem(s)) {}

void Simulation::step() { dem_.step(); }

void Simulation::save_state(const std::string& path) const { save_state_file(path, dem_.state()); }

void Simulation::load_state(const std::string& path) { dem_.set_state(load_state_file(path)); }

}  // namespace fluidbed
