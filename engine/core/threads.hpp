#pragma once
// How many threads a simulation uses inside a step. Results do not depend on it (the particle
// step gathers forces in a fixed order), only the speed does.
#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace fluidbed {

// requested <= 0: one per core.
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace fluidbed

namespace fluidbed {

// Thread t's share [begin, end) of n items split into `threads` contiguous blocks (the first
// n % threads blocks one longer). The same split in every loop of a step keeps each particle's
// data on one core.
template <class Int>
inline void split_range(Int n, int t, int threads, Int& begin, Int& end) {
  const Int q = n / threads, rem = n % threads;
  const Int tt = static_cast<Int>(t);
  begin = tt * q + std::min(tt, rem);
  end = begin + q + (tt < rem ? 1 : 0);
}

}  // namespace fluidbed

namespace fluidbed {

// Per-particle work is split between threads in blocks of this many consecutive particles, and
// sums over particles (kinetic energy, porosity, drag per cell) are taken block by block and the
// block sums added in block order: the same bits for any number of threads.
inline constexpr std::size_t kParticleBlock = 64;

inline std::size_t particle_blocks(std::size_t n) { return (n + kParticleBlock - 1) / kParticleBlock; }

// Thread t's particles [begin, end): whole blocks, the same split in every loop of a step, so each
// particle's data stays on one core.
inline void particle_range(std::size_t n, int t, int threads, std::size_t& begin, std::size_t& end) {
  std::size_t b0 = 0, b1 = 0;
  split_range(particle_blocks(n), t, threads, b0, b1);
  begin = std::min(n, b0 * kParticleBlock);
  end = std::min(n, b1 * kParticleBlock);
}

}  // namespace fluidbed

namespace fluidbed {

// Thread t's particles [begin, end) from a split's bounds (T + 1 entries, as DemSolver balances
// them), or the even block split when the bounds are for another thread count.
inline void split_particles(const std::vector<std::size_t>& bounds, std::size_t n, int t,
                            int threads, std::size_t& begin, std::size_t& end) {
  if (bounds.size() == static_cast<std::size_t>(threads) + 1 && bounds.back() == n) {
    begin = bounds[static_cast<std::size_t>(t)];
    end = bounds[static_cast<std::size_t>(t) + 1];
  } else {
    particle_range(n, t, threads, begin, end);
  }
}

}  // namespace fluidbed

namespace fluidbed {

// The calling thread's number t of T in the current parallel region (0 of 1 outside one or
// without OpenMP).
inline void this_thread(int& t, int& T) {
#ifdef _OPENMP
  t = omp_get_thread_num();
  T = omp_get_num_threads();
#else
  t = 0;
  T = 1;
#endif
}

}  // namespace fluidbed
