#pragma once
// Contact history (the accumulated displacements of eqs 13-17) in flat arrays, no map.
//
// Pair contacts: each pair is owned by its lower index, which keeps up to kSlots partners. The
// history of the previous step is read and the new step's written into a second buffer, so
// contacts that ended simply vanish. Wall contacts: one slot per particle and wall.
#include <cstdint>
#include <vector>

namespace fluidbed {

struct PairHistory {
  static constexpr int kSlots = 12;  // owned contacts per particle (a dense 2D packing has <= 6)
  std::vector<std::uint8_t> count;   // per particle
  std::vector<std::int32_t> partner; // [i * kSlots + k]
  std::vector<double> dn, dt;        // m, normal and tangential displacement

  void resize(std::size_t n) {
    count.assign(n, 0);
    partner.assign(n * kSlots, -1);
    dn.assign(n * kSlots, 0.0);
    dt.assign(n * kSlots, 0.0);
  }
  void clear_counts() { std::fill(count.begin(), count.end(), std::uint8_t{0}); }

  // Slot of (lo, hi) or -1.
  int find(std::int32_t lo, std::int32_t hi) const {
    const std::size_t base = static_cast<std::size_t>(lo) * kSlots;
    for (int k = 0; k < count[lo]; ++k)
      if (partner[base + k] == hi) return static_cast<int>(base) + k;
    return -1;
  }
  std::size_t total() const {
    std::size_t t = 0;
    for (auto c : count) t += c;
    return t;
  }
};

struct WallHistory {
  int walls = 0;
  std::vector<std::uint8_t> active;  // [i * walls + w]
  std::vector<double> dn, dt;        // m

  void resize(std::size_t n, int wall_count) {
    walls = wall_count;
    active.assign(n * wall_count, 0);
    dn.assign(n * wall_count, 0.0);
    dt.assign(n * wall_count, 0.0);
  }
};

}  // namespace fluidbed
