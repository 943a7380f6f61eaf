// One validation pass over a scene: impossible values are refused with the key's name. Each
// number is checked against the range the field table gives it (scene/settings.hpp), then the
// fields against each other and the geometry.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "dem/walls.hpp"
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
  void operator()(std::string_view key, const std::optional<double>& v,
                  const FieldInfo& info) const {
    if (v) check(key, *v, info.range, false);
  }
  // Names, flags, paths and the seed: their type, checked by the loader, is all they need.
  template <class T>
  void operator()(std::string_view, const T&, const FieldInfo&) const {}
};

// The memory the machine has free: MemAvailable from /proc/meminfo, or the physical memory where
// that cannot be read.
double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream row(line);
    std::string name;
    double kb = 0.0;
    if (row >> name >> kb && name == "MemAvailable:") return kb * 1024.0;
  }
  return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  return text;
}

// What a scene's size would cost before anything is allocated, in doubles so that no count
// overflows: a value that would exhaust the machine (10^9 particles or gas cells) is refused here
// with the key that makes it large, instead of growing until the machine swaps. The figures per
// item are upper bounds of what `/usr/bin/time -v` measured on the packing scene: about 0.7 kB
// per particle, 0.9 kB per gas cell, 60 MB at start. The domain's size costs nothing by itself
// (the placement draws its sites from the lattice's shape, scene/lattice.hpp, and the neighbour
// grid has about two cells per particle), but its rows and columns are counted in integers.
void refuse_unaffordable(const Settings& s) {
  const auto& d = s.domain;
  const auto& p = s.particles;
  const double span = 1e8 * p.diameter;
  if (!(d.height <= span)) refuse("domain.height", "is more than 10^8 particles.diameter high");
  if (!(d.width <= span)) refuse("domain.width", "is more than 10^8 particles.diameter wide");
  const double particles = 1024.0 * p.count;
  const double gas = s.gas.enabled ? 1024.0 * static_cast<double>(s.gas.cells_x) *
                                         static_cast<double>(s.gas.cells_y)
                                   : 0.0;
  const double total = 60e6 + particles + gas;
  const double available = available_memory_bytes();
  if (!(total <= available)) {
    const bool gas_larger = gas > particles;
    refuse(gas_larger ? "gas.cells_x times gas.cells_y" : "particles.count",
           "makes the run need about " + gigabytes(total) + " of memory (" +
               (gas_larger ? gigabytes(gas) + " for the gas cells"
                           : gigabytes(particles) + " for the particles") +
               "), more than the " + gigabytes(available) + " this machine has free");
  }
}

}  // namespace

void validate(const Settings& s) {
  Settings table = s;  // the field table's visitors take non-const references
  visit_sections(table, [](std::string_view name, auto& section) {
    visit_fields(section, RangeCheck{std::string(name)});
  });

  const auto& d = s.domain;
  const auto& p = s.particles;
  if (!p.packing_scene.empty() && (p.packing_friction || p.packing_rolling_friction))
    refuse(p.packing_friction ? "particles.packing_friction" : "particles.packing_rolling_friction",
           "is for a bed that packs itself; with particles.packing_scene, that scene's contact "
           "values make the packing (set them there)");
  if (p.diameter > d.width || p.diameter > d.height)
    refuse("particles.diameter", "is larger than the domain");
  // The slab must hold one layer: spheres move in x-y between the front and back walls.
  if (d.thickness < p.diameter)
    refuse("domain.thickness", "must be at least particles.diameter (one layer of spheres)");
  if (p.fill_height > d.height) refuse("particles.fill_height", "is above domain.height");
  refuse_unaffordable(s);
  if (p.placement == Placement::Lattice || p.placement == Placement::Packed) {
    const double top = p.fill_height > 0.0 ? p.fill_height : d.height;
    const auto cells = LatticeShape(d.width, top, p.diameter).size();
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
    if (d.width / g.cells_x < p.diameter ||
        (d.height + s.inlet.plenum_height) / g.cells_y < p.diameter)
      refuse("gas.cells_x",
             "makes gas cells smaller than a particle (cells must be at least one "
             "particles.diameter wide and high)");
  }
  const auto& law = s.contact;
  const bool hertz = law.law == ContactLaw::HertzMindlin;
  if (hertz && !slab_has_depth(d, p.diameter))
    refuse("contact.law", "= \"hertz_mindlin\" needs a thick slab (domain.thickness above "
                          "particles.diameter); a monolayer has the linear law only");
  const std::pair<const char*, bool> hertz_keys[] = {
      {"contact.youngs_modulus", law.youngs_modulus.has_value()},
      {"contact.poisson_ratio", law.poisson_ratio.has_value()},
      {"contact.restitution", law.restitution.has_value()}};
  for (const auto& [name, given] : hertz_keys) {
    if (hertz && !given) refuse(name, "is needed with contact.law = \"hertz_mindlin\"");
    if (!hertz && given)
      refuse(name, "is for contact.law = \"hertz_mindlin\"; the linear law takes "
                   "contact.stiffness and contact.damping");
  }
  const auto& c = s.coupling;
  if (c.void_fraction == VoidFraction::Smoothed && !(c.void_fraction_length > 0.0))
    refuse("coupling.void_fraction_length",
           "must be positive with coupling.void_fraction = \"smoothed\" (the smoothing length, m)");
  if (c.void_fraction == VoidFraction::Exact && c.void_fraction_length != 0.0)
    refuse("coupling.void_fraction_length",
           "is set but coupling.void_fraction is \"exact\" (set it to \"smoothed\" to use it)");
  // Each probe inside the gas domain (the bed's box; on its walls allowed).
  for (std::size_t k = 0; k < s.diagnostics.probes.size(); ++k) {
    const ProbePoint& q = s.diagnostics.probes[k];
    char where[96];
    std::snprintf(where, sizeof where, "has probe %zu at (%g, %g) m", k + 1, q.x, q.y);
    if (!g.enabled)
      refuse("diagnostics.probes",
             std::string(where) + " but the scene has no gas ([gas]) to measure");
    const double bottom = -s.inlet.plenum_height;
    if (q.x < 0.0 || q.x > d.width || q.y < bottom || q.y > d.height) {
      char domain[96];
      std::snprintf(domain, sizeof domain, "x in [0, %g] m, y in [%g, %g] m", d.width, bottom,
                    d.height);
      refuse("diagnostics.probes", std::string(where) + " outside the gas domain (" + domain +
                                       "): move it, or set diagnostics.probes = [] for none");
    }
  }
  if (s.inlet.distributor_resistance > 0.0) {
    const auto& in = s.inlet;
    if (!(in.plenum_height > 0.0))
      refuse("inlet.distributor_resistance",
             "needs a plenum under the plate (inlet.plenum_height > 0)");
    const double dy = (d.height + in.plenum_height) / g.cells_y, rows = in.plenum_height / dy;
    if (std::fabs(rows - std::round(rows)) > 1e-6)
      refuse("inlet.distributor_resistance",
             "needs the floor on a gas cell boundary: inlet.plenum_height a whole number of "
             "cells high (now " + std::to_string(rows) + ")");
  }
  if (s.inlet.jet_width * s.inlet.jets > d.width)
    refuse("inlet.jet_width", "times inlet.jets is wider than domain.width");
}

}  // namespace fluidbed
