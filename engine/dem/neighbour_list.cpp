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

bool NeighbourList::stale(const Particles& p) const {
  if (!built_) return true;
  const double limit = 0.25 * skin_ * skin_;  // (skin / 2)^2
  const std::size_t n = p.size();
  for (std::size_t k = 0; k < n; ++k) {
    const double dx = p.x[k] - x_ref_[k], dy = p.y[k] - y_ref_[k];
    if (dx * dx + dy * dy > limit) return true;
  }
  return false;
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
    out.dt.push_back(dt[k]);
  }
}

void NeighbourList::build(const Particles& p, const PairContacts* seed) {
  if (!seed && seeded_) seed = &seed_;
  const std::size_t n = p.size();
  grid_.build(p.x, p.y);
  keys_.clear();
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* r = p.radius.data();
  grid_.for_each_candidate_pair([&](int a, int b) {
    const double dx = x[b] - x[a], dy = y[b] - y[a];
    const double reach = r[a] + r[b] + skin_;
    if (dx * dx + dy * dy >= reach * reach) return;
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    keys_.push_back(lo << 32 | hi);
  });
  std::sort(keys_.begin(), keys_.end());

  // Merge the old history (sorted by pair) into the new slots.
  std::vector<std::int32_t> ni(keys_.size()), nj(keys_.size());
  std::vector<double> ndn(keys_.size(), 0.0), ndt(keys_.size(), 0.0);
  std::vector<std::uint8_t> nt(keys_.size(), 0);
  const std::vector<std::int32_t>& oi = seed ? seed->i : i;
  const std::vector<std::int32_t>& oj = seed ? seed->j : j;
  const std::vector<double>& odn = seed ? seed->dn : dn;
  const std::vector<double>& odt = seed ? seed->dt : dt;
  std::size_t o = 0;
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    ni[k] = static_cast<std::int32_t>(keys_[k] >> 32);
    nj[k] = static_cast<std::int32_t>(keys_[k] & 0xffffffffu);
    while (o < oi.size() && (static_cast<std::uint64_t>(oi[o]) << 32 | static_cast<std::uint32_t>(oj[o])) < keys_[k]) ++o;
    if (o < oi.size() && oi[o] == ni[k] && oj[o] == nj[k]) {
      const bool was_touching = seed ? true : touching[o] != 0;
      if (was_touching) {
        ndn[k] = odn[o];
        ndt[k] = odt[o];
        nt[k] = 1;
      }
    }
  }
  i.swap(ni);
  j.swap(nj);
  dn.swap(ndn);
  dt.swap(ndt);
  touching.swap(nt);
  seeded_ = false;
  seed_.clear();
  const std::size_t m = i.size();
  fx.assign(m, 0.0);
  fy.assign(m, 0.0);
  ft.assign(m, 0.0);
  ratio.assign(m, 0.0);

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

  x_ref_ = p.x;
  y_ref_ = p.y;
  built_ = true;
  ++builds_;
}

}  // namespace fluidbed
