#pragma once
// Rigid planar walls of the slab. A wall is a plane with unit normal (nx, ny) pointing into the
// domain; a particle centre's distance from it is nx x + ny y - offset. The front and back walls
// (z = 0 and z = thickness) are perpendicular to the plane of motion: with the slab at least one
// diameter thick (checked when the scene is read) and centres on its mid-plane they never press
// on a particle, so the planar kernel leaves them out.
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed {

struct Wall {
  double nx, ny;   // inward unit normal
  double offset;   // m
  std::string name;
};

inline std::vector<Wall> slab_walls(const DomainSettings& d) {
  std::vector<Wall> walls = {
      {0.0, 1.0, 0.0, "bottom"},
      {1.0, 0.0, 0.0, "left"},
      {-1.0, 0.0, -d.width, "right"},
  };
  if (d.top_wall) walls.push_back({0.0, -1.0, -d.height, "top"});
  return walls;
}

}  // namespace fluidbed
