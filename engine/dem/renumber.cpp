// The particles' numbering (dem/dem_solver.hpp): the solver's arrays sorted by neighbour cell every
// renumber_steps, and the conversions between that order and the particles' ids.
//
// Why: a contact reads both particles' arrays. Placed in strips, a particle's neighbours have
// nearby numbers; once a bed has mixed they have any, and a bed whose arrays no longer fit the
// cache then waits on memory at every contact (docs/speed.md: 1.3 x the contacts' time at 240,000
// particles mixed within strips, 1.8 x mixed over the bed). Sorting by cell brings neighbours back
// together and gives each thread (a range of places) a part of the bed.
//
// Results: the sums over a particle's contacts run in the (i, j) order of places, so a
// renumbering changes the last bits from then on, never more. The schedule is a fixed count of
// steps (never the neighbour list's rebuilds, which depend on the skin), the sort depends on the
// state alone (not on the threads), and the order is saved with the state: every result is the
// same bits for any thread count and skin, and a resumed run continues the same bits.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/permute.hpp"
#include "dem/dem_solver.hpp"

namespace fluidbed {
namespace {

// Cells of the sort (a diameter wide) run in strips of this many cells across, each strip bottom
// to top, row by row: a particle's neighbours are then within three rows of a strip (a hundred
// places or so) in any bed, however wide. 32 diameters: about the lattice start's 40-diameter
// strips.
constexpr int kStripCells = 32;

// The pair history with its particles renamed (a particle k becomes to[k]), each pair's first
// particle the lower again and the pairs sorted (in place: at 240,000 spheres it holds some
// 10 MB). The shear displacement is the pair's first
// particle's relative to its second: in a thick slab a vector, which swapping the two reverses;
// in a monolayer a component along the tangent n rotated by +90 degrees, which reverses with n,
// so that the component itself stays.
void rename_pairs(PairContacts& h, const std::vector<std::int32_t>& to, bool depth) {
  const std::size_t m = h.size();
  for (std::size_t k = 0; k < m; ++k) {
    const std::int32_t p = to[static_cast<std::size_t>(h.i[k])];
    const std::int32_t q = to[static_cast<std::size_t>(h.j[k])];
    h.i[k] = std::min(p, q);
    h.j[k] = std::max(p, q);
    if (depth && p > q) {
      h.ds[k] = -h.ds[k];
      h.ds_y[k] = -h.ds_y[k];
      h.ds_z[k] = -h.ds_z[k];
    }
  }
  std::vector<std::int32_t> by(m);
  std::iota(by.begin(), by.end(), 0);
  std::sort(by.begin(), by.end(), [&](std::int32_t u, std::int32_t v) {
    const auto a = static_cast<std::size_t>(u), b = static_cast<std::size_t>(v);
    return h.i[a] < h.i[b] || (h.i[a] == h.i[b] && h.j[a] < h.j[b]);
  });
  for (auto* v : {&h.i, &h.j}) gather_by(*v, by);
  for (auto* v : {&h.dn, &h.ds, &h.ds_y, &h.ds_z}) gather_by(*v, by);
}

// Every per-particle array of p and the walls' history reordered (core/permute.hpp).
void gather_particles(Particles& p, WallHistory& wh, const std::vector<std::int32_t>& from) {
  for (auto* v : p.all_arrays()) gather_by(*v, from);
  const auto nw = static_cast<std::size_t>(wh.walls);
  for (auto* v : {&wh.dn, &wh.ds, &wh.ds_y, &wh.ds_z}) gather_by(*v, from, nw);
  gather_by(wh.active, from, nw);
}

// The inverse of a permutation.
std::vector<std::int32_t> inverse(const std::vector<std::int32_t>& p) {
  std::vector<std::int32_t> q(p.size());
  for (std::size_t k = 0; k < p.size(); ++k)
    q[static_cast<std::size_t>(p[k])] = static_cast<std::int32_t>(k);
  return q;
}

}  // namespace

void DemSolver::renumber() {
  const Particles& P = state_.particles;
  const std::size_t n = P.size();
  const int nx = std::max(1, static_cast<int>(width_ / cell_));
  const int ny = std::max(1, static_cast<int>(height_ / cell_));
  const int strips = (nx + kStripCells - 1) / kStripCells;
  // A counting sort by the key of each particle's cell, stable in the present order.
  std::vector<std::int32_t> key(n);
  std::vector<std::int32_t> start(static_cast<std::size_t>(strips) * ny * kStripCells + 1, 0);
  auto cell_of = [&](double v, int cells) {  // beyond the box (or not a number): the edge cell
    const double c = v / cell_;
    return c >= 1.0 ? static_cast<int>(std::min(c, cells - 1.0)) : 0;
  };
  for (std::size_t s = 0; s < n; ++s) {
    const int cx = cell_of(P.x[s], nx), cy = cell_of(P.y[s], ny);
    const int strip = cx / kStripCells;
    key[s] = (strip * ny + cy) * kStripCells + (cx - strip * kStripCells);
    ++start[static_cast<std::size_t>(key[s]) + 1];
  }
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<std::int32_t> from(n);
  for (std::size_t s = 0; s < n; ++s) {
    std::int32_t& next = start[static_cast<std::size_t>(key[s])];
    from[static_cast<std::size_t>(next++)] = static_cast<std::int32_t>(s);
  }
  bool same = true;
  for (std::size_t s = 0; s < n && same; ++s) same = from[s] == static_cast<std::int32_t>(s);
  if (same) return;
  reorder(from);
  if (on_renumber_) on_renumber_(from);
}

// The particle at place from[s] moves to place s: every per-particle array, the walls' history and
// the pairs' (renamed), the ids; the neighbour list and the threads' split are rebuilt at the
// next step.
void DemSolver::reorder(const std::vector<std::int32_t>& from) {
  const std::size_t n = state_.particles.size();
  PairContacts h;
  list_.export_history(h);
  gather_particles(state_.particles, state_.walls, from);
  gather_by(overlap_, from);
  if (id_.empty()) {
    id_.resize(n);
    std::iota(id_.begin(), id_.end(), 0);
  }
  gather_by(id_, from);
  place_ = inverse(id_);
  rename_pairs(h, inverse(from), depth_);
  list_.import_history(std::move(h));
  near_threads_ = 0;
}

DemState DemSolver::exported_state() const {
  DemState copy = state_;
  list_.export_history(copy.pairs);
  if (id_.empty()) return copy;
  // From places to ids: what is at place s goes to id_[s].
  gather_particles(copy.particles, copy.walls, place_);
  rename_pairs(copy.pairs, id_, depth_);
  copy.order = id_;
  return copy;
}

void DemSolver::set_state(DemState s) {
  if (s.particles.size() != state_.particles.size())
    throw InputError("state has " + std::to_string(s.particles.size()) +
                     " particles but the scene has " + std::to_string(state_.particles.size()));
  if (s.walls.walls != static_cast<int>(walls_.size()))
    throw InputError("state was saved with " + std::to_string(s.walls.walls) +
                     " walls but the scene has " + std::to_string(walls_.size()));
  if (s.particles.has_depth() != depth_)
    throw InputError(std::string("state was saved for a ") + (depth_ ? "monolayer" : "thick slab") +
                     " but the scene is a " + (depth_ ? "thick slab" : "monolayer"));
  const std::size_t n = s.particles.size();
  if (!s.order.empty()) {
    std::vector<std::uint8_t> seen(n, 0);
    bool ok = s.order.size() == n;
    for (std::size_t k = 0; ok && k < n; ++k) {
      const std::int32_t v = s.order[k];
      ok = v >= 0 && static_cast<std::size_t>(v) < n && !seen[static_cast<std::size_t>(v)];
      if (ok) seen[static_cast<std::size_t>(v)] = 1;
    }
    if (!ok) throw InputError("state's particle order is not a permutation of its particles");
  }
  id_ = std::move(s.order);
  s.order.clear();
  PairContacts pairs = std::move(s.pairs);
  s.pairs.clear();
  state_ = std::move(s);
  if (id_.empty()) {
    place_.clear();
    list_.import_history(std::move(pairs));
  } else {
    // From ids to the saved order: place s takes particle id_[s].
    place_ = inverse(id_);
    gather_particles(state_.particles, state_.walls, id_);
    rename_pairs(pairs, place_, depth_);
    list_.import_history(std::move(pairs));
  }
  // Built here so that the history is in place (hashes, exports) before the next step, which
  // builds again on its threads.
  rebuild(0, 1, 0, state_.particles.size());
  near_threads_ = 0;
}

// In ids, read in place (no copy of the state): the same bits whatever order the solver keeps.
std::uint64_t DemSolver::configuration_hash() const {
  PairContacts pairs;
  list_.export_history(pairs);
  if (!id_.empty()) rename_pairs(pairs, id_, depth_);
  Fnv1a h;
  // A per-particle array (rows of `per` values) by id.
  auto by_id = [&](const auto& v, std::size_t per) {
    if (id_.empty()) return h.values(v);
    for (const std::int32_t at : place_)
      for (std::size_t c = 0; c < per; ++c) h.value(v[static_cast<std::size_t>(at) * per + c]);
  };
  const Particles& P = state_.particles;
  for (const auto* v : {&P.x, &P.y, &P.vx, &P.vy, &P.w, &P.ax, &P.ay, &P.aw}) by_id(*v, 1);
  if (depth_)  // a monolayer's hash is what it was before the depth arrays existed
    for (const auto* v : {&P.z, &P.vz, &P.wx, &P.wy, &P.az, &P.awx, &P.awy}) by_id(*v, 1);
  // The touching pairs in (i, j) order: the same whatever the skin or the rebuild times.
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    h.value(pairs.i[k]);
    h.value(pairs.j[k]);
    h.value(pairs.dn[k]);
    h.value(pairs.ds[k]);
    if (depth_) {
      h.value(pairs.ds_y[k]);
      h.value(pairs.ds_z[k]);
    }
  }
  const WallHistory& wh = state_.walls;
  const auto nw = static_cast<std::size_t>(wh.walls);
  by_id(wh.active, nw);
  by_id(wh.dn, nw);
  by_id(wh.ds, nw);
  if (depth_) {
    by_id(wh.ds_y, nw);
    by_id(wh.ds_z, nw);
  }
  return h.digest();
}

}  // namespace fluidbed
