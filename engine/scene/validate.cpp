// One validation pass over a scene: impossible values are refused with the key's name. Each
// number is checked against the range the field table gives it (scene/settings.hpp), then the
// fields against each other and the geometry.
#include <string>

#include "core/errors.hpp"
#include "scene/lattice.hpp"
#include "scene/scene_loader.hpp"

namespace fluidbed {
namespace {

[[noreturn]] void refuse(const std::string& key, const std::string& why) {
  throw InputError(key + " " + why);
}

// Why a number is outside its field's range, in the words used for each kind of range.
std::string out_of_range(const Range& r, double v, bool integer) {
  const std::string got = " (got " + std::to_string(v) + ")";
  if (!r.bounded_below() && !r.bounded_above()) return "must be finite";
  if (!r.bounded_above() && r.low == 0.0 && !integer)
    return r.low_open ? "must be positive" + got : "must not be negative" + got;
  if (!r.bounded_above() && !r.low_open)
    return "must be at least " + std::to_string(static_cast<long long>(r.low));
  return "must be in " + r.text() + got;
}

// Every number against the range the field table gives it, in table order.
struct RangeCheck {
  std::string section;
  void check(std::string_view key, double v, const Range& r, bool integer) const {
    if (!r.contains(v)) refuse(section + "." + std::string(key), out_of_range(r, v, integer));
  }
  void operator()(std::string_view key, double v, const FieldInfo& info) const {
    check(key, v, info.range, false);
  }
  void operator()(std::string_view key, int v, const FieldInfo& info) const {
    check(key, v, info.range, true);
  }
  // Names, flags, paths and the seed: their type, checked by the loader, is all they need.
  template <class T>
  void operator()(std::string_view, const T&, const FieldInfo&) const {}
};

}  // namespace

void validate(const Settings& s) {
  Settings table = s;  // the field table's visitors take non-const references
  visit_sections(table, [](std::string_view name, auto& section) {
    visit_fields(section, RangeCheck{std::string(name)});
  });

  const auto& d = s.domain;
  const auto& p = s.particles;
  if (p.diameter > d.width || p.diameter > d.height)
    refuse("particles.diameter", "is larger than the domain");
  // The slab must hold one layer: spheres move in x-y between the front and back walls.
  if (d.thickness < p.diameter)
    refuse("domain.thickness", "must be at least particles.diameter (one layer of spheres)");
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

  const auto& g = s.gas;
  if (g.enabled) {
    // Porosity counts each sphere in the cells it straddles; the exact split assumes a sphere
    // is cut by at most one grid line each way.
    if (d.width / g.cells_x < p.diameter || d.height / g.cells_y < p.diameter)
      refuse("gas.cells_x",
             "makes gas cells smaller than a particle (cells must be at least one "
             "particles.diameter wide and high)");
  }
  if (s.inlet.jet_width * s.inlet.jets > d.width)
    refuse("inlet.jet_width", "times inlet.jets is wider than domain.width");
}

}  // namespace fluidbed
