#pragma once
// Independent runs side by side: `workers` threads take tasks from a shared counter, each task
// on one thread, so each simulation keeps to one core and the results do not depend on how many
// threads there are. The first exception a task throws is rethrown once every thread finished.
// Used by the sweep (run/velocity_sweep.cpp), the studies and reproduce.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "core/threads.hpp"

namespace fluidbed {

class RunPool {
 public:
  explicit RunPool(int workers) : workers_(resolve_threads(workers)) {}  // <= 0: one per core
  int workers() const { return workers_; }

  // Tasks in list order (a long chain first keeps one thread while the others share the rest).
  void run(const std::vector<std::function<void()>>& tasks) const {
    for_each(tasks.size(), {}, [&](std::size_t k) { tasks[k](); });
  }

  // f(k) for k in [0, n), results in index order. ORDER, a permutation of [0, n), is the order
  // the points are taken in (heaviest first); empty: 0, 1, 2, ...
  template <class R>
  std::vector<R> map(std::size_t n, const std::function<R(std::size_t)>& f,
                     const std::vector<std::size_t>& order = {}) const {
    std::vector<R> out(n);
    for_each(n, order, [&](std::size_t k) { out[k] = f(k); });
    return out;
  }

 private:
  template <class F>
  void for_each(std::size_t n, const std::vector<std::size_t>& order, F&& task) const {
    std::atomic<std::size_t> next{0};
    std::mutex error_mutex;
    std::exception_ptr error;
    const auto worker = [&] {
      for (std::size_t q; (q = next.fetch_add(1)) < n;) {
        try {
          task(order.empty() ? q : order[q]);
        } catch (...) {
          std::lock_guard lock(error_mutex);
          if (!error) error = std::current_exception();
        }
      }
    };
    const auto threads = std::min(static_cast<std::size_t>(workers_), n);
    if (threads <= 1) {
      worker();
    } else {
      std::vector<std::thread> pool;
      for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
      for (auto& t : pool) t.join();
    }
    if (error) std::rethrow_exception(error);
  }

  int workers_;
};

}  // namespace fluidbed
