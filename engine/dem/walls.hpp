#pragma once
// Rigid planar walls of the slab. A wall is a plane with unit normal (nx, ny, nz) pointing into
// the domain; a particle centre's distance from it is nx x + ny y + nz z - offset. The front and
// back walls (z = 0 and z = thickness) are perpendicular to the plane of motion: in a monolayer
// (the slab one diameter thick, centres on its mid-plane) they never press on a particle, so they
// are left out; in a thicker slab, where particles move in z, they are real contacts.
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed {

struct Wall {
  double nx, ny;   // inward unit normal (x, y)
  double offset;   // m
  std::string name;
  double nz = 0.0;  // inward unit normal (z): nonzero only for the front and back walls
};

// Whether a scene's particles move in three dimensions: the slab is thicker than one diameter
// (by more than round-off; the paper's bed is exactly one diameter).
inline bool slab_has_depth(const DomainSettings& d, double diameter) {
  return d.thickness > diameter * (1.0 + 1e-9);
}

// The walls of the slab; depth: the front and back walls too (a thick slab).
inline std::vector<Wall> slab_walls(const DomainSettings& d, bool depth = false) {
  std::vector<Wall> walls = {
      {0.0, 1.0, 0.0, "bottom"},
      {1.0, 0.0, 0.0, "left"},
      {-1.0, 0.0, -d.width, "right"},
  };
  if (depth) {
    walls.push_back({0.0, 0.0, 0.0, "front", 1.0});
    walls.push_back({0.0, 0.0, -d.thickness, "back", -1.0});
  }
  // Last, so that a bed packed without a lid can start a scene with one (WallHistory::add_walls).
  if (d.top_wall) walls.push_back({0.0, -1.0, -d.height, "top"});
  return walls;
}

}  // namespace fluidbed
