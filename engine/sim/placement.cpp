#include "sim/placement.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>
#include <utility>

#include "core/errors.hpp"
#include "core/random.hpp"
#include "dem/walls.hpp"
#include "scene/lattice.hpp"

namespace fluidbed {

std::string scene_path(const Settings& s, const std::string& path) {
  std::filesystem::path p(path);
  if (p.is_absolute()) return p.string();
  return (std::filesystem::path(s.source_dir) / p).lexically_normal().string();
}

Particles place_particles(const Settings& s) {
  const auto& ps = s.particles;
  Particles p;
  const std::size_t n = static_cast<std::size_t>(ps.count);
  p.resize(n);
  for (std::size_t i = 0; i < n; ++i) p.set_sphere(i, ps.diameter, ps.density);
  // A thick slab: the particles move in three dimensions, from the slab's mid-plane unless the
  // placement says otherwise.
  const bool depth = slab_has_depth(s.domain, ps.diameter);
  if (depth) p.add_depth(0.5 * s.domain.thickness);
  if (ps.placement == Placement::Single) {
    p.x[0] = ps.x;
    p.y[0] = ps.y;
    p.vx[0] = ps.vx;
    p.vy[0] = ps.vy;
    p.w[0] = ps.spin;
  } else if (ps.placement == Placement::Lattice) {
    const double top = ps.fill_height > 0.0 ? ps.fill_height : s.domain.height;
    const LatticeShape lattice(s.domain.width, top, ps.diameter);
    const std::size_t cells = lattice.size();
    if (cells < n) throw InputError("particles.count: only " + std::to_string(cells) + " fit");
    // Partial Fisher-Yates: the first n of a seeded shuffle of the cells choose which are filled.
    // Only the entries the shuffle moved are stored (the others hold their own number), so a tall
    // domain with few particles costs n entries, not one per cell.
    std::unordered_map<std::size_t, std::size_t> moved;
    auto at = [&](std::size_t k) {
      const auto it = moved.find(k);
      return it == moved.end() ? k : it->second;
    };
    std::vector<std::size_t> order(n);
    SplitMix64 rng(ps.seed);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = i + rng.below(cells - i);
      const std::size_t chosen = at(k);
      moved[k] = at(i);
      order[i] = chosen;
    }
    // The particles are then numbered strip by strip (vertical strips 40 diameters wide, the
    // paper's bed is one), along the rows inside a strip, bottom to top: a particle's neighbours
    // have numbers within about a strip's width of its own, however wide the bed, so the step's
    // arrays are read in cache order and each thread's block of particles is a compact region.
    const double strip = 40.0 * ps.diameter;
    auto key = [&](std::size_t site) {
      return std::pair{static_cast<long>(lattice.site(site).x / strip), site};
    };
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    for (std::size_t i = 0; i < n; ++i) {
      const LatticeSite site = lattice.site(order[i]);
      p.x[i] = site.x;
      p.y[i] = site.y;
    }
    // In a thick slab each sphere's z is drawn uniformly across the slab (its lattice cell is a
    // column through the depth: spheres of neighbouring cells cannot overlap at any z), from a
    // stream of its own so that the cells chosen are those of the monolayer with the same seed.
    // Spheres at random depths meet as they fall and settle into a packing in three dimensions;
    // on a few fixed layers they would never touch across layers.
    if (depth) {
      SplitMix64 zrng(ps.seed ^ 0x5a17u);
      const double r = 0.5 * ps.diameter, span = s.domain.thickness - ps.diameter;
      for (std::size_t i = 0; i < n; ++i) p.z[i] = r + span * zrng.uniform();
    }
  } else {
    throw InputError("particles.placement \"" + option_string(ps.placement) +
                     "\" does not place particles");
  }
  return p;
}

DemState load_scene_state(const Settings& s) {
  const std::string path = scene_path(s, s.particles.state_file);
  DemState st = load_state_file(path);
  auto& p = st.particles;
  if (p.size() != static_cast<std::size_t>(s.particles.count))
    throw InputError(path + ": holds " + std::to_string(p.size()) +
                     " particles but particles.count is " + std::to_string(s.particles.count));
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::fabs(2.0 * p.radius[i] - s.particles.diameter) > 1e-12 * s.particles.diameter)
      throw InputError(path + ": particle diameters differ from particles.diameter");
    p.set_sphere(i, s.particles.diameter, s.particles.density);
  }
  return st;
}

}  // namespace fluidbed
