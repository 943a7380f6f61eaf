#pragma once
// Neighbour search on a uniform cell grid: a counting sort of particles into square cells at
// least one largest diameter wide, so touching pairs lie in the same or adjacent cells. The
// particles' positions and radii are copied in cell order, so the three cells of a row around a
// particle are one contiguous run to scan. No allocation after the first build at a given size.
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

  void build(const std::vector<double>& x, const std::vector<double>& y,
             const std::vector<double>& r) {
    const std::size_t n = x.size();
    cell_of_.resize(n);
    id_.resize(n);
    xs_.resize(n);
    ys_.resize(n);
    rs_.resize(n);
    std::fill(start_.begin(), start_.end(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      const int c = cell_index(x[i], y[i]);
      cell_of_[i] = c;
      ++start_[c + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    cursor_.assign(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const int k = cursor_[cell_of_[i]]++;
      id_[k] = static_cast<std::int32_t>(i);
      xs_[k] = x[i];
      ys_[k] = y[i];
      rs_[k] = r[i];
    }
  }

  // The runs of the cell-ordered arrays that hold particle i's cell and the 8 around it: one run
  // per row, [begin[q], end[q]) for q < the returned count (at most 3).
  int near_runs(std::size_t i, int begin[3], int end[3]) const {
    const int c = cell_of_[i];
    const int cx = c % nx_, cy = c / nx_;
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx_ - 1);
    int runs = 0;
    for (int qy = std::max(cy - 1, 0); qy <= std::min(cy + 1, ny_ - 1); ++qy) {
      const int row = qy * nx_;
      begin[runs] = start_[row + x0];  // three cells in a row are contiguous
      end[runs] = start_[row + x1 + 1];
      ++runs;
    }
    return runs;
  }

  // In cell order: particle index, centre and radius.
  const std::int32_t* ids() const { return id_.data(); }
  const double* xs() const { return xs_.data(); }
  const double* ys() const { return ys_.data(); }
  const double* rs() const { return rs_.data(); }

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
  std::vector<std::int32_t> id_;
  std::vector<double> xs_, ys_, rs_;
};

}  // namespace fluidbed
