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
  gather_begin.assign(particles + 1, 0);
  built_ = false;
  built_once_ = false;
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
  // cells around it, sorted (a handful, by insertion). No sort of the whole list, no allocation
  // once warm. The filter is branch-free (every candidate is written, the count advances only
  // for the ones kept): whether a neighbour is within reach follows no pattern a branch
  // predictor could learn.
  ni_.clear();
  nj_.clear();
  ndn_.clear();
  nds_.clear();
  nt_.clear();
  near_.resize(n + 1);
  std::int32_t* nb = near_.data();
  // The old history is merged particle by particle, through the old list's first_begin
  // (each particle's old entries, sorted by j), which is overwritten as the new one is made.
  // A saved history (`seed`) is merged afterwards instead.
  const bool carry = !seed && built_once_;
  std::int32_t* fb = first_begin.data();
  for (std::size_t a = 0; a < n; ++a) {
    const double xa = x[a], ya = y[a], ra = r[a] + skin_;
    const auto ia = static_cast<std::int32_t>(a);
    int count = 0;
    grid_.for_each_near(xa, ya, [&](std::int32_t b) {
      const double dx = x[b] - xa, dy = y[b] - ya;
      const double reach = ra + r[b];
      nb[count] = b;
      count += (b > ia) & (dx * dx + dy * dy < reach * reach);
    });
    for (int q = 1; q < count; ++q) {  // insertion sort: a handful, nearly in order
      const std::int32_t v = nb[q];
      int u = q;
      for (; u > 0 && nb[u - 1] > v; --u) nb[u] = nb[u - 1];
      nb[u] = v;
    }
    std::int32_t o = carry ? fb[a] : 0;
    const std::int32_t oe = carry ? fb[a + 1] : 0;
    fb[a] = static_cast<std::int32_t>(ni_.size());
    for (int q = 0; q < count; ++q) {
      const std::int32_t b = nb[q];
      while (o < oe && j[o] < b) ++o;
      const bool kept = o < oe && j[o] == b && touching[o] != 0;
      ni_.push_back(ia);
      nj_.push_back(b);
      ndn_.push_back(kept ? dn[o] : 0.0);
      nds_.push_back(kept ? ds[o] : 0.0);
      nt_.push_back(kept ? 1 : 0);
    }
  }
  const std::size_t m = ni_.size();
  fb[n] = static_cast<std::int32_t>(m);

  if (seed) {  // a saved history (sorted by pair) merged into the new slots
    auto key = [](std::int32_t u, std::int32_t v) {
      return static_cast<std::uint64_t>(u) << 32 | static_cast<std::uint32_t>(v);
    };
    std::size_t o = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const std::uint64_t kk = key(ni_[k], nj_[k]);
      while (o < seed->i.size() && key(seed->i[o], seed->j[o]) < kk) ++o;
      if (o < seed->i.size() && seed->i[o] == ni_[k] && seed->j[o] == nj_[k]) {
        ndn_[k] = seed->dn[o];
        nds_[k] = seed->ds[o];
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

  // Gather lists: entries are sorted by i, so each particle's "first" entries are contiguous
  // (first_begin, made above); its "second" entries come from a stable counting sort by j.
  second_begin.assign(n + 1, 0);
  for (std::size_t k = 0; k < m; ++k) ++second_begin[j[k] + 1];
  for (std::size_t q = 0; q < n; ++q) second_begin[q + 1] += second_begin[q];
  second_pair.resize(m);
  counts_.assign(second_begin.begin(), second_begin.end() - 1);
  for (std::size_t k = 0; k < m; ++k) second_pair[counts_[j[k]]++] = static_cast<std::int32_t>(k);
  gather_begin.resize(n + 1);
  gather.resize(2 * m);
  std::int32_t g = 0;
  for (std::size_t q = 0; q < n; ++q) {
    gather_begin[q] = g;
    for (std::int32_t u = second_begin[q]; u < second_begin[q + 1]; ++u) gather[g++] = ~second_pair[u];
    for (std::int32_t k = first_begin[q]; k < first_begin[q + 1]; ++k) gather[g++] = k;
  }
  gather_begin[n] = g;

  x_ref_.assign(p.x.begin(), p.x.end());
  y_ref_.assign(p.y.begin(), p.y.end());
  built_ = true;
  built_once_ = true;
  ++builds_;
}

}  // namespace fluidbed
