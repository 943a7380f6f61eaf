#include "dem/neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fluidbed {

void NeighbourList::configure(double width, double height, double dmax, double skin,
                              std::size_t particles, int threads, bool depth) {
  skin_ = skin;
  depth_ = depth;
  // Cells wide enough that every candidate pair is in the same or adjacent cells, and no more
  // cells than about twice the particles, so a sparse scene (one dropped sphere) costs nothing.
  const double sparse =
      std::sqrt(width * height / (2.0 * static_cast<double>(std::max<std::size_t>(particles, 1))));
  grid_.configure(width, height, std::max(dmax + skin, sparse));
  for (PairSlots& s : set_) {
    s = PairSlots{};
    s.first_begin.assign(particles + 1, 0);
  }
  cur_ = 0;
  found_.assign(static_cast<std::size_t>(std::max(threads, 1)), Found{});
  for (Found& f : found_) f.near.assign(particles + 1, 0);
  offset_.assign(found_.size() + 1, 0);
  built_ = false;
  built_once_ = false;
}

namespace {

// The two largest squared moves of particles [begin, end) since (xr, yr, zr), into m1 >= m2. No
// early exit and no branch: a loop that vectorises is faster over a few thousand.
template <bool Depth>
void two_largest_moves(const double* x, const double* y, const double* z, const double* xr,
                       const double* yr, const double* zr, std::size_t begin, std::size_t end,
                       double& m1, double& m2) {
  for (std::size_t k = begin; k < end; ++k) {
    const double dx = x[k] - xr[k], dy = y[k] - yr[k];
    const double dz = Depth ? z[k] - zr[k] : 0.0;
    const double d2 = dx * dx + dy * dy + dz * dz;
    m2 = std::max(m2, std::min(m1, d2));
    m1 = std::max(m1, d2);
  }
}

}  // namespace

void NeighbourList::displacement(const Particles& p, std::size_t begin, std::size_t end,
                                 double moved2[2]) const {
  double m1 = 0.0, m2 = 0.0;
  if (built_) {
    const double* x = p.x.data();
    const double* y = p.y.data();
    const double* xr = x_ref_.data();
    const double* yr = y_ref_.data();
    // A thick slab's candidates are within reach in 3D: its z moves count too.
    if (depth_)
      two_largest_moves<true>(x, y, p.z.data(), xr, yr, z_ref_.data(), begin, end, m1, m2);
    else
      two_largest_moves<false>(x, y, nullptr, xr, yr, nullptr, begin, end, m1, m2);
  }
  moved2[0] = m1;
  moved2[1] = m2;
}

bool NeighbourList::stale(double largest, double second) const {
  return !built_ || std::sqrt(largest) + std::sqrt(second) > skin_;
}

bool NeighbourList::stale(const Particles& p) const {
  double m[2];
  displacement(p, 0, p.size(), m);
  return stale(m[0], m[1]);
}

void NeighbourList::import_history(PairContacts saved) {
  seed_ = std::move(saved);
  seeded_ = true;
  built_ = false;
}

void NeighbourList::export_history(PairContacts& out) const {
  out.clear();
  const PairSlots& s = slots();
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (!s.touching[k]) continue;
    out.i.push_back(s.i[k]);
    out.j.push_back(s.j[k]);
    out.dn.push_back(s.dn[k]);
    out.ds.push_back(s.ds[k]);
    if (depth_) {
      out.ds_y.push_back(s.ds_y[k]);
      out.ds_z.push_back(s.ds_z[k]);
    }
  }
}

// Particles [begin, end): for each a in turn, the partners b > a within reach in the nine cells
// around it, sorted (a handful, by insertion), with the history of the pairs the last list held
// (each particle's old entries are sorted by j: a merge). The reach test is branch-free (every
// candidate is written, the count advances only for the ones kept): whether a neighbour is within
// reach follows no pattern a branch predictor could learn. Writes out's arrays from 0 and
// first_begin[a] relative to them.
template <bool Depth>
void NeighbourList::find_pairs(const Particles& p, bool carry, std::size_t begin, std::size_t end,
                               Found& out, std::vector<std::int32_t>& first_begin) {
  const PairSlots& old = set_[cur_];
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* z = p.z.data();  // a thick slab's (empty in a monolayer)
  const double* r = p.radius.data();
  const std::int32_t* ids = grid_.ids();
  const double* xs = grid_.xs();
  const double* ys = grid_.ys();
  const double* rs = grid_.rs();
  std::int32_t* nb = out.near.data();
  std::size_t m = 0;
  for (std::size_t a = begin; a < end; ++a) {
    const double xa = x[a], ya = y[a], ra = r[a] + skin_;
    const double za = Depth ? z[a] : 0.0;
    const auto ia = static_cast<std::int32_t>(a);
    int rb[3], re[3];
    const int runs = grid_.near_runs(a, rb, re);
    int count = 0;
    for (int q = 0; q < runs; ++q)
      for (int k = rb[q]; k < re[q]; ++k) {
        const double dx = xs[k] - xa, dy = ys[k] - ya;
        const double reach = ra + rs[k];
        const std::int32_t b = ids[k];
        // In a thick slab the reach is in 3D: the spheres at other depths of the same column
        // are no candidates.
        const double dz = Depth ? z[b] - za : 0.0;
        nb[count] = b;
        count += (b > ia) & (dx * dx + dy * dy + dz * dz < reach * reach);
      }
    for (int q = 1; q < count; ++q) {  // insertion sort: a handful
      const std::int32_t v = nb[q];
      int u = q;
      for (; u > 0 && nb[u - 1] > v; --u) nb[u] = nb[u - 1];
      nb[u] = v;
    }
    if (m + static_cast<std::size_t>(count) > out.i.size()) {
      out.resize(std::max(2 * out.i.size(), m + count + 64), depth_);
    }
    std::int32_t o = carry ? old.first_begin[a] : 0;
    const std::int32_t oe = carry ? old.first_begin[a + 1] : 0;
    first_begin[a] = static_cast<std::int32_t>(m);
    for (int q = 0; q < count; ++q, ++m) {
      const std::int32_t b = nb[q];
      while (o < oe && old.j[o] < b) ++o;
      const bool kept = o < oe && old.j[o] == b && old.touching[o] != 0;
      out.i[m] = ia;
      out.j[m] = b;
      out.dn[m] = kept ? old.dn[o] : 0.0;
      out.ds[m] = kept ? old.ds[o] : 0.0;
      out.touching[m] = kept ? 1 : 0;
      if (depth_) {
        out.ds_y[m] = kept ? old.ds_y[o] : 0.0;
        out.ds_z[m] = kept ? old.ds_z[o] : 0.0;
      }
    }
  }
  out.count = m;
}

void NeighbourList::build(const Particles& p, int t, int T, std::size_t begin, std::size_t end) {
  const std::size_t n = p.size();
  const int next = 1 - cur_;
  const bool seeded = seeded_;  // read by every thread before merge_seed clears it
  const bool carry = !seeded && built_once_;
  PairSlots& out = set_[next];
  Found& f = found_[static_cast<std::size_t>(t)];
#pragma omp single
  grid_.build(p.x, p.y, p.radius);
  // Thread 0's pairs go straight into the new set (its arrays lent to the scratch and returned);
  // the others' are copied behind them.
  auto lend = [](Found& a, PairSlots& b) {
    std::swap(a.i, b.i);
    std::swap(a.j, b.j);
    std::swap(a.dn, b.dn);
    std::swap(a.ds, b.ds);
    std::swap(a.ds_y, b.ds_y);
    std::swap(a.ds_z, b.ds_z);
    std::swap(a.touching, b.touching);
  };
  if (t == 0) lend(f, out);
  if (depth_) {
    find_pairs<true>(p, carry, begin, end, f, out.first_begin);
  } else {
    find_pairs<false>(p, carry, begin, end, f, out.first_begin);
  }
  if (t == 0) lend(f, out);
#pragma omp barrier
#pragma omp single
  {
    offset_[0] = 0;
    for (int u = 0; u < T; ++u) offset_[u + 1] = offset_[u] + found_[u].count;
    const std::size_t m = offset_[T];
    out.resize(m, depth_);
    out.first_begin[n] = static_cast<std::int32_t>(m);
    active.resize(m);
    code.resize(m);
    contact_scratch.resize(m, depth_);
    x_ref_.resize(n);
    y_ref_.resize(n);
    if (depth_) z_ref_.resize(n);
    cur_ = next;
    built_ = true;
    built_once_ = true;
    ++builds_;
  }
  // Each thread: its pairs behind those of the threads before it, its particles' starts shifted
  // there, its reference positions.
  const std::size_t off = offset_[t];
  if (t > 0) {
    std::copy_n(f.i.begin(), f.count, out.i.begin() + off);
    std::copy_n(f.j.begin(), f.count, out.j.begin() + off);
    std::copy_n(f.dn.begin(), f.count, out.dn.begin() + off);
    std::copy_n(f.ds.begin(), f.count, out.ds.begin() + off);
    std::copy_n(f.touching.begin(), f.count, out.touching.begin() + off);
    if (depth_) {
      std::copy_n(f.ds_y.begin(), f.count, out.ds_y.begin() + off);
      std::copy_n(f.ds_z.begin(), f.count, out.ds_z.begin() + off);
    }
    for (std::size_t a = begin; a < end; ++a) out.first_begin[a] += static_cast<std::int32_t>(off);
  }
  std::copy(p.x.begin() + begin, p.x.begin() + end, x_ref_.begin() + begin);
  std::copy(p.y.begin() + begin, p.y.begin() + end, y_ref_.begin() + begin);
  if (depth_) std::copy(p.z.begin() + begin, p.z.begin() + end, z_ref_.begin() + begin);
    // The whole list in place before any thread reads another's part (a thread's last start,
    // first_begin[end], is the next thread's first, shifted by it above).
#pragma omp barrier
  if (seeded) {  // a saved history, merged once the whole list is in place
#pragma omp single
    merge_seed();
  }
}

// The saved history (sorted by pair) merged into the new slots; no other history is carried.
void NeighbourList::merge_seed() {
  PairSlots& s = slots();
  auto key = [](std::int32_t u, std::int32_t v) {
    return static_cast<std::uint64_t>(u) << 32 | static_cast<std::uint32_t>(v);
  };
  std::size_t o = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::uint64_t kk = key(s.i[k], s.j[k]);
    while (o < seed_.i.size() && key(seed_.i[o], seed_.j[o]) < kk) ++o;
    if (o < seed_.i.size() && seed_.i[o] == s.i[k] && seed_.j[o] == s.j[k]) {
      s.dn[k] = seed_.dn[o];
      s.ds[k] = seed_.ds[o];
      if (depth_ && !seed_.ds_y.empty()) {
        s.ds_y[k] = seed_.ds_y[o];
        s.ds_z[k] = seed_.ds_z[o];
      }
      s.touching[k] = 1;
    }
  }
  seeded_ = false;
  seed_ = PairContacts{};  // its memory too (a renumbering imports the whole history)
}

}  // namespace fluidbed
