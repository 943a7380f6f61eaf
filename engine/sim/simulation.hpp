#pragma once
// A scene's model put together: the particles now; the gas and the coupler join here, each
// knowing nothing of the other. Owns the state; one call advances it by one time step.
#include <cstdint>
#include <string>

#include "dem/dem_solver.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

class Simulation {
 public:
  explicit Simulation(const Settings& s);

  void step();

  const Settings& settings() const { return settings_; }
  const DemSolver& dem() const { return dem_; }
  DemSolver& dem() { return dem_; }
  double time() const { return dem_.time(); }
  std::int64_t steps() const { return dem_.state().step; }
  std::size_t particle_count() const { return dem_.particles().size(); }

  bool has_gas() const { return false; }
  double pressure_drop() const { return 0.0; }  // Pa, bottom to top on the symmetry line

  std::uint64_t state_hash() const { return dem_.state_hash(); }
  void save_state(const std::string& path) const;
  // Bit-exact restart: replaces the whole state, time included.
  void load_state(const std::string& path);

 private:
  Settings settings_;
  DemSolver dem_;
};

}  // namespace fluidbed
