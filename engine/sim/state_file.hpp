#pragma once
// A simulation's whole state in one file: the particle block (dem/state_io, which alone is
// enough to start a new experiment from a packed bed), then, when the scene has gas, the gas
// fields and the coupler's pending exchange, so that a coupled run restarts bit-exactly.
#include <string>

#include "cfd/gas_solver.hpp"
#include "coupling/coupler.hpp"
#include "dem/dem_solver.hpp"

namespace fluidbed {

struct StateFile {
  DemState dem;
  bool has_gas = false;
  GasState gas;
  CouplingState coupling;
  int since_gas_step = 0;
};

void save_simulation_state(const std::string& path, const StateFile& f);
StateFile load_simulation_state(const std::string& path);

}  // namespace fluidbed
