// One validation pass over a scene: impossible values are refused with the key's name.
#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "scene/lattice.hpp"
#include "scene/scene_loader.hpp"

namespace fluidbed {
namespace {

[[noreturn]] void refuse(const std::string& key, const std::string& why) {
  throw InputError(key + " " + why);
}
void positive(const std::string& key, double v) {
  if (!(v > 0.0)) refuse(key, "must be positive (got " + std::to_string(v) + ")");
}
void non_negative(const std::string& key, double v) {
  if (!(v >= 0.0)) refuse(key, "must not be negative (got " + std::to_string(v) + ")");
}
}  // namespace

void validate(const Settings& s) {

  const auto& d = s.domain;
  positive("domain.width", d.width);
  positive("domain.height", d.height);
  positive("domain.thickness", d.thickness);

  const auto& p = s.particles;
  if (p.count < 1) refuse("particles.count", "must be at least 1");
  positive("particles.diameter", p.diameter);
  positive("particles.density", p.density);
  positive("particles.packing_time", p.packing_time);
  if (p.diameter > d.width || p.diameter > d.height)
    refuse("particles.diameter", "is larger than the domain");
  // The slab must hold one layer: spheres move in x-y between the front and back walls.
  if (d.thickness < p.diameter)
    refuse("domain.thickness", "must be at least particles.diameter (one layer of spheres)");
  non_negative("particles.fill_height", p.fill_height);
  if (p.fill_height > d.height) refuse("particles.fill_height", "is above domain.height");
  if (p.placement == Placement::Lattice || p.placement == Placement::Packed) {
    const double top = p.fill_height > 0.0 ? p.fill_height : d.height;
    const auto cells = lattice_sites(d.width, top, p.diameter).size();
    if (static_cast<std::size_t>(p.count) > cells)
      refuse("particles.count", "is " + std::to_string(p.count) + " but only " +
                                    std::to_string(cells) + " particles fit in the domain");
  }
  if (p.placement == Placement::Single) {
    if (p.count != 1) refuse("particles.count", "must be 1 for placement = \"single\"");
    const double r = 0.5 * p.diameter;
    if (p.x < r || p.x > d.width - r) refuse("particles.x", "puts the particle through a wall");
    if (p.y < r || (d.top_wall && p.y > d.height - r))
      refuse("particles.y", "puts the particle through a wall");
  }
  if (p.placement == Placement::State && p.state_file.empty())
    refuse("particles.state_file", "is needed for placement = \"state\"");

  const auto& c = s.contact;
  positive("contact.stiffness", c.stiffness);
  non_negative("contact.tangential_stiffness_ratio", c.tangential_stiffness_ratio);
  non_negative("contact.damping", c.damping);
  non_negative("contact.tangential_damping_ratio", c.tangential_damping_ratio);
  non_negative("contact.friction", c.friction);
  non_negative("contact.skin", c.skin);

  positive("time.dt", s.time.dt);
  non_negative("time.end", s.time.end);
  if (!std::isfinite(s.physics.gravity)) refuse("physics.gravity", "must be finite");

  const auto& g = s.gas;
  positive("gas.density", g.density);
  positive("gas.viscosity", g.viscosity);
  if (g.cells_x < 3) refuse("gas.cells_x", "must be at least 3");
  if (g.cells_y < 3) refuse("gas.cells_y", "must be at least 3");
  positive("gas.tolerance", g.tolerance);
  if (g.max_iterations < 1) refuse("gas.max_iterations", "must be at least 1");
  non_negative("gas.preconditioner_refresh", g.preconditioner_refresh);
  if (g.enabled) {
    // Porosity counts each sphere in the cells it straddles; the exact split assumes a sphere
    // is cut by at most one grid line each way.
    if (d.width / g.cells_x < p.diameter || d.height / g.cells_y < p.diameter)
      refuse("gas.cells_x", "makes gas cells smaller than a particle (cells must be at least one "
                            "particles.diameter wide and high)");
  }
  non_negative("inlet.superficial_velocity", s.inlet.superficial_velocity);
  positive("inlet.jet_width", s.inlet.jet_width);
  if (s.inlet.jets < 1) refuse("inlet.jets", "must be at least 1");
  if (s.inlet.jet_width * s.inlet.jets > d.width)
    refuse("inlet.jet_width", "times inlet.jets is wider than domain.width");
  if (s.coupling.particle_steps_per_gas_step < 1)
    refuse("coupling.particle_steps_per_gas_step", "must be at least 1");

  const BubbleSection& b = s.bubbles;
  if (!(b.threshold > 0.0 && b.threshold < 1.0))
    refuse("bubbles.threshold", "must be in (0, 1) (got " + std::to_string(b.threshold) + ")");
  non_negative("bubbles.min_diameter", b.min_diameter);
  positive("bubbles.interval", b.interval);
  if (!(b.slug_fraction > 0.0 && b.slug_fraction <= 1.0))
    refuse("bubbles.slug_fraction", "must be in (0, 1]");
  non_negative("bubbles.cell_size", b.cell_size);
  non_negative("bubbles.window", b.window);
  if (b.min_track_frames < 1) refuse("bubbles.min_track_frames", "must be at least 1");
  non_negative("bubbles.eruption_gap", b.eruption_gap);
  if (!(b.slugging_min_fraction > 0.0 && b.slugging_min_fraction <= 1.0))
    refuse("bubbles.slugging_min_fraction", "must be in (0, 1]");
  if (!(b.spouting_min_fraction > 0.0 && b.spouting_min_fraction <= 1.0))
    refuse("bubbles.spouting_min_fraction", "must be in (0, 1]");
  if (!(b.bed_min_fraction >= 0.0 && b.bed_min_fraction < 1.0))
    refuse("bubbles.bed_min_fraction", "must be in [0, 1)");

  positive("diagnostics.output_interval", s.diagnostics.output_interval);
  non_negative("diagnostics.averaging_start", s.diagnostics.averaging_start);
  if (!(s.diagnostics.overlap_limit > 0.0 && s.diagnostics.overlap_limit <= 1.0))
    refuse("diagnostics.overlap_limit", "must be in (0, 1]");
}

}  // namespace fluidbed
