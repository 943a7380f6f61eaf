#pragma once
// Contact history in flat arrays, no map.
//
// PairContacts is the saved form of the pair history: the touching pairs (i < j), sorted by
// (i, j), with their accumulated displacements (eqs 13-17). The solver's working copy lives in
// the neighbour list (one slot per candidate pair) and is exported to this form for state files
// and hashes. WallHistory keeps one slot per particle and wall.
#include <cstdint>
#include <vector>

namespace fluidbed {

struct PairContacts {
  std::vector<std::int32_t> i, j;  // particle indices, i < j, sorted by (i, j)
  std::vector<double> dn, dt;      // m, normal and tangential displacement
  std::size_t size() const { return i.size(); }
  void clear() {
    i.clear();
    j.clear();
    dn.clear();
    dt.clear();
  }
};

struct WallHistory {
  int walls = 0;
  std::vector<std::uint8_t> active;  // [i * walls + w]
  std::vector<double> dn, dt;        // m

  void resize(std::size_t n, int wall_count) {
    walls = wall_count;
    active.assign(n * wall_count, 0);
    dn.assign(n * wall_count, 0.0);
    dt.assign(n * wall_count, 0.0);
  }
};

}  // namespace fluidbed
