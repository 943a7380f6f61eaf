#pragma once
// The candidate contact pairs: every pair closer than R_i + R_j + skin, found on a cell grid and
// rebuilt only when two particles together may have moved more than the skin since the last
// build. Each slot carries its pair's contact history, so contacts survive rebuilds (merged by
// pair).
//
// Entries are sorted by (i, j), and each particle sums its pair forces in that order
// (DemSolver::particle_pass), so the forces - and every result - are the same bits whatever the
// skin, the rebuild times or the number of threads.
//
// A build runs on every thread of the step's parallel region: thread t finds the pairs of its own
// particles (their first particle in its range) and the threads' lists are joined in thread order,
// which is the (i, j) order.
#include <cstdint>
#include <vector>

#include "dem/cell_grid.hpp"
#include "dem/contact_history.hpp"
#include "dem/particles.hpp"

namespace fluidbed {

// The pair slots with their history, sorted by (i, j), and where each particle's entries begin.
// The per-slot arrays of a list of pairs: the list itself (PairSlots) and each thread's share
// while it is built (NeighbourList::Found).
struct SlotArrays {
  std::vector<std::int32_t> i, j;
  std::vector<double> dn, ds;          // m, normal and tangential (shear) displacement
  // In a thick slab the shear displacement is a vector: ds holds its x component, these its y
  // and z components (empty in a monolayer, where ds is along the contact's tangent).
  std::vector<double> ds_y, ds_z;
  std::vector<std::uint8_t> touching;  // touching at the last evaluation
  std::size_t size() const { return i.size(); }
  // Every array to m slots (the depth components only in a thick slab).
  void resize(std::size_t m, bool depth) {
    i.resize(m);
    j.resize(m);
    dn.resize(m);
    ds.resize(m);
    touching.resize(m);
    if (depth) {
      ds_y.resize(m);
      ds_z.resize(m);
    }
  }
};

struct PairSlots : SlotArrays {
  // Entries [first_begin[p], first_begin[p + 1]) have i == p (n + 1 values).
  std::vector<std::int32_t> first_begin;
};

// Scratch of the pair pass, per slot: the touching pairs' results, compact (dem/pair_kernel.hpp).
struct ContactScratch {
  std::vector<double> dn, ds, fx, fy, ft, ratio, dashpot, friction;
  std::vector<double> roll;  // the rolling resistance's torque on i (with contact.rolling_friction)
  std::vector<std::int32_t> sliding;
  // A thick slab's further components: the force on i along z, the x and y components of the
  // unit-lever torque n x F_t (ft is its z component: the torque on i is R_i n x F_t, on j
  // R_j n x F_t), the shear displacement's y and z components and the rolling torque's x and y.
  std::vector<double> fz, ftx, fty, ds_y, ds_z, roll_x, roll_y;
  void resize(std::size_t m, bool depth) {
    for (auto* v : {&dn, &ds, &fx, &fy, &ft, &ratio, &dashpot, &friction, &roll}) v->resize(m);
    sliding.resize(m);
    if (depth)
      for (auto* v : {&fz, &ftx, &fty, &ds_y, &ds_z, &roll_x, &roll_y}) v->resize(m);
  }
};

class NeighbourList {
 public:
  // dmax: largest diameter (m); skin (m) >= 0; threads: the most that will call build().
  // depth: the particles move in three dimensions (a thick slab): the candidates are the pairs
  // within reach in 3D (found in the x-y cells, which hold every depth), and the displacements
  // that make the list stale count z.
  void configure(double width, double height, double dmax, double skin, std::size_t particles,
                 int threads = 1, bool depth = false);

  // Largest and second-largest squared displacement of particles [begin, end) since the last
  // build; moved2[0] >= moved2[1].
  void displacement(const Particles& p, std::size_t begin, std::size_t end, double moved2[2]) const;
  // True when no build has been made, or when the two largest displacements (of all particles)
  // sum to more than the skin: only then can a pair have come from beyond R_i + R_j + skin to
  // touching, or a particle from beyond R + skin of a wall (its displacement alone above it).
  bool stale(double largest, double second) const;
  // The same test for all particles (serial callers).
  bool stale(const Particles& p) const;

  // Rebuilds the candidates at the particles' current positions, carrying over the history of
  // pairs that remain (or taking it from a saved history, import_history). Called by each of the
  // T threads of a parallel region with its particles [begin, end) (ascending ranges that cover
  // all particles, in thread order); it holds barriers, so every thread of the team must call
  // it. Outside a parallel region: build(p).
  void build(const Particles& p, int t, int T, std::size_t begin, std::size_t end);
  void build(const Particles& p) { build(p, 0, 1, 0, p.size()); }
  // The touching pairs and their displacements, sorted by (i, j).
  void export_history(PairContacts& out) const;
  // Replaces the history with a saved one; the next stale() is true.
  void import_history(PairContacts saved);

  std::size_t size() const { return slots().size(); }
  std::int64_t builds() const { return builds_; }
  bool built() const { return built_; }

  const PairSlots& slots() const { return set_[cur_]; }
  PairSlots& slots() { return set_[cur_]; }

  // Scratch of the force pass, per slot: touching, coincident or apart; the touching slots (each
  // thread's from its first slot on); their contacts' results.
  std::vector<std::uint8_t> code;
  std::vector<std::int32_t> active;
  ContactScratch contact_scratch;

 private:
  // One thread's pairs while a build runs (thread 0 writes straight into the new slot set).
  struct Found : SlotArrays {
    std::vector<std::int32_t> near;   // scratch: one particle's partners
    std::size_t count = 0;
  };
  template <bool Depth>
  void find_pairs(const Particles& p, bool carry, std::size_t begin, std::size_t end, Found& out,
                  std::vector<std::int32_t>& first_begin);
  void merge_seed();

  CellGrid grid_;
  double skin_ = 0.0;
  bool depth_ = false;
  std::vector<double> x_ref_, y_ref_, z_ref_;
  bool built_ = false;
  bool built_once_ = false;  // the slot set holds a list (its history)
  bool seeded_ = false;
  PairContacts seed_;
  std::int64_t builds_ = 0;
  PairSlots set_[2];  // the current slot set and the one the next build writes
  int cur_ = 0;
  std::vector<Found> found_;     // per thread (found_[0] is used only for its counts and scratch)
  std::vector<std::size_t> offset_;  // per thread: where its pairs start in the new set
};

}  // namespace fluidbed
