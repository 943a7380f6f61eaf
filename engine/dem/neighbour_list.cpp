#include "dem/neighbour_list.hpp"

#include <algorithm>
#include <cmath>

namespace fluidbed {

void NeighbourList::configure(double width, double height, double dmax, double skin,
                              std::size_t particles) {
  skin_ = skin;
  // Cells wide enough that every candidate pair is in the same or adjacent cells, and no more
  // cells than about twice the particles, so a sparse scene (one dropped sphere) costs nothing.
  const double sparse = std::sqrt(width * height / (2.0 * static_cast<double>(std::max<std::size_t>(particles, 1))));
  grid_.configure(width, height, std::max(dmax + skin, sparse));
  first_begin.assign(particles + 1, 0);
  second_begin.assign(particles + 1, 0);
  built_ = false;
}

bool NeighbourList::stale(const Particles& p) const { return stale(p, 0, p.size()); }

bool NeighbourList::stale(const Particles& p, std::size_t begin, std::size_t end) const {
  if (!built_) return true;
  const double limit = 0.25 * skin_ * skin_;  // (skin / 2)^2
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* xr = x_ref_.data();
  const double* yr = y_ref_.data();
  // No early exit: a branch-free loop that vectorises is faster over a few thousand particles.
  bool moved = false;
  for (std::size_t k = begin; k < end; ++k) {
    const double dx = x[k] - xr[k], dy = y[k] - yr[k];
    moved |= dx * dx + dy * dy > limit;
  }
  return moved;
}

void NeighbourList::import_history(const PairContacts& saved) {
  seed_ = saved;
  seeded_ = true;
  built_ = false;
}

void NeighbourList::export_history(PairContacts& out) const {
  out.clear();
  for (std::size_t k = 0; k < i.size(); ++k) {
    if (!touching[k]) continue;
    out.i.push_back(i[k]);
    out.j.push_back(j[k]);
    out.dn.push_back(dn[k]);
    out.ds.push_back(ds[k]);
  }
}

void NeighbourList::build(const Particles& p, const PairContacts* seed) {
  if (!seed && seeded_) seed = &seed_;
  const std::size_t n = p.size();
  grid_.build(p.x, p.y);
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* r = p.radius.data();
  // Candidates in (i, j) order straight away: for each i in turn, the partners j > i in the nine
  // cells around it, sorted (a handful). No sort of the whole list, no allocation once warm.
  ni_.clear();
  nj_.clear();
  for (std::size_t a = 0; a < n; ++a) {
    near_.clear();
    const double xa = x[a], ya = y[a], ra = r[a] + skin_;
    grid_.for_each_near(xa, ya, [&](std::int32_t b) {
      if (static_cast<std::size_t>(b) <= a) return;
      const double dx = x[b] - xa, dy = y[b] - ya;
      const double reach = ra + r[b];
      if (dx * dx + dy * dy < reach * reach) near_.push_back(b);
    });
    std::sort(near_.begin(), near_.end());
    for (std::int32_t b : near_) {
      ni_.push_back(static_cast<std::int32_t>(a));
      nj_.push_back(b);
    }
  }
  const std::size_t m = ni_.size();

  // Merge the old history (sorted by pair) into the new slots.
  ndn_.assign(m, 0.0);
  nds_.assign(m, 0.0);
  nt_.assign(m, 0);
  const std::vector<std::int32_t>& oi = seed ? seed->i : i;
  const std::vector<std::int32_t>& oj = seed ? seed->j : j;
  const std::vector<double>& odn = seed ? seed->dn : dn;
  const std::vector<double>& ods = seed ? seed->ds : ds;
  auto key = [](std::int32_t u, std::int32_t v) {
    return static_cast<std::uint64_t>(u) << 32 | static_cast<std::uint32_t>(v);
  };
  std::size_t o = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const std::uint64_t kk = key(ni_[k], nj_[k]);
    while (o < oi.size() && key(oi[o], oj[o]) < kk) ++o;
    if (o < oi.size() && oi[o] == ni_[k] && oj[o] == nj_[k]) {
      const bool was_touching = seed ? true : touching[o] != 0;
      if (was_touching) {
        ndn_[k] = odn[o];
        nds_[k] = ods[o];
        nt_[k] = 1;
      }
    }
  }
  i.swap(ni_);
  j.swap(nj_);
  dn.swap(ndn_);
  ds.swap(nds_);
  touching.swap(nt_);
  seeded_ = false;
  seed_.clear();
  fx.resize(m);
  fy.resize(m);
  ft.resize(m);
  ratio.resize(m);
  active.resize(m);

  // Gather lists: entries are sorted by i, so each particle's "first" entries are contiguous;
  // its "second" entries come from a stable counting sort by j.
  first_begin.assign(n + 1, 0);
  second_begin.assign(n + 1, 0);
  for (std::size_t k = 0; k < m; ++k) {
    ++first_begin[i[k] + 1];
    ++second_begin[j[k] + 1];
  }
  for (std::size_t q = 0; q < n; ++q) {
    first_begin[q + 1] += first_begin[q];
    second_begin[q + 1] += second_begin[q];
  }
  second_pair.resize(m);
  counts_.assign(second_begin.begin(), second_begin.end() - 1);
  for (std::size_t k = 0; k < m; ++k) second_pair[counts_[j[k]]++] = static_cast<std::int32_t>(k);

  x_ref_.assign(p.x.begin(), p.x.end());
  y_ref_.assign(p.y.begin(), p.y.end());
  built_ = true;
  ++builds_;
}

}  // namespace fluidbed
