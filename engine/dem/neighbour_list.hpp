#pragma once
// The candidate contact pairs: every pair closer than R_i + R_j + skin, found on a cell grid and
// rebuilt only when some particle has moved more than half the skin since the last build. Each
// slot carries its pair's contact history, so contacts survive rebuilds (merged by pair), and
// the results of the last force evaluation, gathered per particle through index lists.
//
// Entries are sorted by (i, j), and each particle gathers its pair forces in a fixed order, so
// the forces - and every result - are the same bits whatever the skin, the rebuild times or the
// number of threads.
#include <cstdint>
#include <vector>

#include "dem/cell_grid.hpp"
#include "dem/contact_history.hpp"
#include "dem/particles.hpp"

namespace fluidbed {

class NeighbourList {
 public:
  // dmax: largest diameter (m); skin (m) >= 0.
  void configure(double width, double height, double dmax, double skin, std::size_t particles);

  // True when a particle has moved more than half the skin since the last build (or never built).
  bool stale(const Particles& p) const;
  // The same test for particles [begin, end) only (a thread's share).
  bool stale(const Particles& p, std::size_t begin, std::size_t end) const;
  // Rebuilds the candidates at the particles' current positions, carrying over the history of
  // pairs that remain (or taking it from `seed`, a saved history, when given).
  void build(const Particles& p, const PairContacts* seed = nullptr);
  // The touching pairs and their displacements, sorted by (i, j).
  void export_history(PairContacts& out) const;
  // Replaces the history with a saved one; the next stale() is true.
  void import_history(const PairContacts& saved);

  std::size_t size() const { return i.size(); }
  std::int64_t builds() const { return builds_; }

  // Per candidate pair.
  std::vector<std::int32_t> i, j;
  std::vector<double> dn, ds;           // m, normal and tangential (shear) displacement; 0 while apart
  std::vector<std::uint8_t> touching;   // touching at the last evaluation
  std::vector<double> fx, fy, ft;       // N: force on i (x, y) and its tangential component
  std::vector<double> ratio;            // overlap ratio (0 while not touching)
  std::vector<std::int32_t> active;     // scratch of the force pass: the touching slots
  // Gather lists: entries [first_begin[p], first_begin[p + 1]) have i == p; the entries with
  // j == p are second_pair[second_begin[p] .. second_begin[p + 1]), in ascending order.
  std::vector<std::int32_t> first_begin, second_begin, second_pair;
  // The same in one list per particle, in the order its forces are summed: the entries where
  // it is second (stored as ~k: the force on it is minus the slot's), then those where it is
  // first (k): gather[gather_begin[p] .. gather_begin[p + 1]).
  std::vector<std::int32_t> gather_begin, gather;

 private:
  CellGrid grid_;
  double skin_ = 0.0;
  std::vector<double> x_ref_, y_ref_;
  bool built_ = false;
  bool built_once_ = false;  // the live arrays and first_begin hold a list (its history)
  bool seeded_ = false;
  PairContacts seed_;
  std::int64_t builds_ = 0;
  std::vector<std::int32_t> counts_;
  // Scratch of build(), swapped with the live arrays (capacity kept: no allocation once warm).
  std::vector<std::int32_t> ni_, nj_, near_;
  std::vector<double> ndn_, nds_;
  std::vector<std::uint8_t> nt_;
};

}  // namespace fluidbed
