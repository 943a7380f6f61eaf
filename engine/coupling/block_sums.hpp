#pragma once
// Sums over particles per gas cell (solid volume for the porosity, drag for the gas), taken so
// that any number of threads gives the same bits: each block of consecutive particles
// (core/threads.hpp) is summed on its own, in particle order, into a short list of (cell, sum)
// in the order the cells were first met; the lists are then added to the cells block by block.
// A thread handles whole blocks in ascending order and appends their lists to its own buffer,
// so reading the buffers thread by thread is reading the blocks in order.
//
// No allocation once warm; the per-cell scratch of a thread is reset through its list of
// touched cells, so the cost is per particle, not per cell.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fluidbed {

class BlockCellSums {
 public:
  // cells: number of gas cells; threads: the most threads that will add at once.
  void configure(int cells, int threads) {
    cells_ = cells;
    lanes_.resize(static_cast<std::size_t>(threads));
    for (auto& l : lanes_) {
      l.mark.assign(static_cast<std::size_t>(cells), -1);
      l.slot.assign(static_cast<std::size_t>(cells), 0);
    }
  }

  // Thread `lane` starts over (call once per round, before its first block).
  void clear(int lane) {
    Lane& l = lanes_[static_cast<std::size_t>(lane)];
    l.out.clear();
  }
  // Starts the next block on thread `lane` (blocks in ascending order).
  void begin_block(int lane) { ++lanes_[static_cast<std::size_t>(lane)].stamp; }
  // Adds (a, b) to cell c in the current block of thread `lane`.
  void add(int lane, int c, double a, double b) {
    Lane& l = lanes_[static_cast<std::size_t>(lane)];
    const auto cu = static_cast<std::size_t>(c);
    if (l.mark[cu] != l.stamp) {
      l.mark[cu] = l.stamp;
      l.slot[cu] = l.out.size();
      l.out.push_back({c, a, b});
    } else {
      Entry& e = l.out[l.slot[cu]];
      e.a += a;
      e.b += b;
    }
  }
  // Adds every block's sums to `a` and `b` (cells entries each; b may be null), blocks in order.
  // Call once all threads are done.
  void add_to(std::vector<double>& a, std::vector<double>* b) const {
    for (const Lane& l : lanes_) {
      for (const Entry& e : l.out) {
        a[static_cast<std::size_t>(e.cell)] += e.a;
        if (b) (*b)[static_cast<std::size_t>(e.cell)] += e.b;
      }
    }
  }
  int threads() const { return static_cast<int>(lanes_.size()); }

 private:
  struct Entry {
    int cell;
    double a, b;
  };
  struct alignas(64) Lane {
    std::vector<Entry> out;
    std::vector<std::int64_t> mark;  // stamp of the block that last touched each cell
    std::vector<std::size_t> slot;   // its entry in `out`
    std::int64_t stamp = 0;          // counts the blocks this lane has begun
  };
  int cells_ = 0;
  std::vector<Lane> lanes_;
};

}  // namespace fluidbed
