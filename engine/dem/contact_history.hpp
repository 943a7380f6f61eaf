#pragma once
// Contact history in flat arrays, no map.
//
// PairContacts is the saved form of the pair history: the touching pairs (i < j), sorted by
// (i, j), with their accumulated displacements (eqs 13-17). The solver's working copy lives in
// the neighbour list (one slot per candidate pair) and is exported to this form for state files
// and hashes. WallHistory keeps one slot per particle and wall.
#include <cstdint>
#include <utility>
#include <vector>

namespace fluidbed {

struct PairContacts {
  std::vector<std::int32_t> i, j;  // particle indices, i < j, sorted by (i, j)
  std::vector<double> dn, ds;      // m, normal and tangential (shear) displacement
  std::vector<double> ds_y, ds_z;  // a thick slab's shear vector (ds its x component); else empty
  std::size_t size() const { return i.size(); }
  void clear() {
    i.clear();
    j.clear();
    dn.clear();
    ds.clear();
    ds_y.clear();
    ds_z.clear();
  }
};

struct WallHistory {
  int walls = 0;
  std::vector<std::uint8_t> active;  // [i * walls + w]
  std::vector<double> dn, ds;        // m, normal and tangential (shear) displacement
  std::vector<double> ds_y, ds_z;    // a thick slab's shear vector (ds its x component); else empty

  // The same history with walls appended (a state saved without a top wall used in a scene with
  // one): the new walls start untouched.
  void add_walls(int wall_count) {
    if (wall_count <= walls) return;
    const std::size_t n = walls > 0 ? active.size() / static_cast<std::size_t>(walls) : 0;
    WallHistory wider;
    wider.resize(n, wall_count, !ds_y.empty());
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < walls; ++c) {
        const std::size_t from = i * walls + c, to = i * wall_count + c;
        wider.active[to] = active[from];
        wider.dn[to] = dn[from];
        wider.ds[to] = ds[from];
        if (!ds_y.empty()) {
          wider.ds_y[to] = ds_y[from];
          wider.ds_z[to] = ds_z[from];
        }
      }
    *this = std::move(wider);
  }

  void resize(std::size_t n, int wall_count, bool depth = false) {
    walls = wall_count;
    active.assign(n * wall_count, 0);
    dn.assign(n * wall_count, 0.0);
    ds.assign(n * wall_count, 0.0);
    ds_y.assign(depth ? n * wall_count : 0, 0.0);
    ds_z.assign(depth ? n * wall_count : 0, 0.0);
  }
};

}  // namespace fluidbed
