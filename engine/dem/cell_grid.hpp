#pragma once
// Neighbour search on a uniform cell grid: a counting sort of particles into square cells at
// least one largest diameter wide, so touching pairs lie in the same or adjacent cells. Each pair
// is visited once (half stencil). No allocation after the first build at a given size.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace fluidbed {

class CellGrid {
 public:
  // Covers [0, width] x [0, height]; particles outside are kept in the edge cells.
  void configure(double width, double height, double min_cell) {
    nx_ = std::max(1, static_cast<int>(width / min_cell));
    ny_ = std::max(1, static_cast<int>(height / min_cell));
    hx_inv_ = nx_ / width;
    hy_inv_ = ny_ / height;
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  }

  void build(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    cell_of_.resize(n);
    sorted_.resize(n);
    std::fill(start_.begin(), start_.end(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      const int c = cell_index(x[i], y[i]);
      cell_of_[i] = c;
      ++start_[c + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    cursor_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) sorted_[cursor_[cell_of_[i]]++] = static_cast<std::int32_t>(i);
  }

  // Calls f(i, j) once for every pair in the same or adjacent cells.
  template <class F>
  void for_each_candidate_pair(F&& f) const {
    for (int cy = 0; cy < ny_; ++cy) {
      for (int cx = 0; cx < nx_; ++cx) {
        const int c = cy * nx_ + cx;
        const int b = start_[c], e = start_[c + 1];
        if (b == e) continue;
        for (int a = b; a < e; ++a) {
          const int i = sorted_[a];
          for (int k = a + 1; k < e; ++k) f(i, sorted_[k]);
        }
        // Forward half of the 8 neighbours: E, and the three above.
        const int nb[4][2] = {{cx + 1, cy}, {cx - 1, cy + 1}, {cx, cy + 1}, {cx + 1, cy + 1}};
        for (const auto& q : nb) {
          if (q[0] < 0 || q[0] >= nx_ || q[1] >= ny_) continue;
          const int d = q[1] * nx_ + q[0];
          const int db = start_[d], de = start_[d + 1];
          for (int a = b; a < e; ++a) {
            const int i = sorted_[a];
            for (int k = db; k < de; ++k) f(i, sorted_[k]);
          }
        }
      }
    }
  }

  // Calls f(j) for every particle in the cell of (x, y) and the 8 around it.
  template <class F>
  void for_each_near(double x, double y, F&& f) const {
    const int c = cell_index(x, y);
    const int cx = c % nx_, cy = c / nx_;
    for (int qy = std::max(cy - 1, 0); qy <= std::min(cy + 1, ny_ - 1); ++qy) {
      const int row = qy * nx_;
      const int b = start_[row + std::max(cx - 1, 0)];
      const int e = start_[row + std::min(cx + 1, nx_ - 1) + 1];  // three cells in a row are contiguous
      for (int k = b; k < e; ++k) f(sorted_[k]);
    }
  }

  int nx() const { return nx_; }
  int ny() const { return ny_; }

 private:
  int cell_index(double x, double y) const {
    // Clamp in floating point first: a particle far outside must not overflow the cast, and a
    // NaN (a run about to fail in words) lands in cell 0 rather than anywhere.
    const double fx = x * hx_inv_, fy = y * hy_inv_;
    const int cx = fx >= 0.0 ? static_cast<int>(std::min(fx, nx_ - 1.0)) : 0;
    const int cy = fy >= 0.0 ? static_cast<int>(std::min(fy, ny_ - 1.0)) : 0;
    return cy * nx_ + cx;
  }

  int nx_ = 1, ny_ = 1;
  double hx_inv_ = 1.0, hy_inv_ = 1.0;
  std::vector<int> start_, cursor_, cell_of_;
  std::vector<std::int32_t> sorted_;
};

}  // namespace fluidbed
