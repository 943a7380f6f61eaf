#include "coupling/coupler.hpp"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <sstream>


#include "cfd/gas_solver.hpp"
#include "core/errors.hpp"
#include "core/threads.hpp"
#include "coupling/drag.hpp"
#include "coupling/porosity.hpp"

namespace fluidbed {

Coupler::Coupler(const GasGrid& grid, const CouplerParams& c, std::size_t particles)
    : grid_(grid),
      rho_f_(c.gas_density),
      mu_f_(c.gas_viscosity),
      pressure_gradient_force_(c.pressure_gradient_force),
      solid_(static_cast<std::size_t>(grid.cells()), 0.0),
      eps_(static_cast<std::size_t>(grid.cells()), 1.0),
      cell_(particles, 0) {
  threads_ = resolve_threads(c.threads);
  parallel_ = threads_ > 1 && particles >= 256;
  sums_.configure(grid.cells(), threads_);
  drag_sums_.configure(grid.cells(), threads_);
  for (auto* v : {&gas_ux_, &gas_uy_, &beta_, &base_fx_, &base_fy_, &drag_x_, &drag_y_, &sum_x_,
                  &sum_y_, &slip_x_, &slip_y_, &slip_, &eps_at_, &ln_eps_at_})
    v->assign(particles, 0.0);
  const auto cells = static_cast<std::size_t>(grid.cells());
  for (auto* v : {&cell_ux_, &cell_uy_, &cell_gx_, &cell_gy_, &ln_eps_, &cell_sum_x_, &cell_sum_y_})
    v->assign(cells, 0.0);
}

// Runs body(t, b, e) on each thread's particles [b, e) (the split's, or even blocks).
template <class F>
void Coupler::per_thread(std::size_t n, const std::vector<std::size_t>& split, F&& body) {
#pragma omp parallel num_threads(threads_) if (parallel_)
  {
    int t = 0, T = 1;
    this_thread(t, T);
    std::size_t b = 0, e = 0;
    split_particles(split, n, t, T, b, e);
    body(t, b, e);
  }
}

const std::vector<double>& Coupler::compute_porosity(const Particles& p, double time,
                                                     const std::vector<std::size_t>& split) {
  for (int t = 0; t < sums_.threads(); ++t) sums_.clear(t);
  per_thread(p.size(), split,
             [&](int t, std::size_t b, std::size_t e) { porosity_range(p, t, b, e); });
  return finish_porosity(time);
}

// Each sphere's shares (the closed forms are the work) summed per cell block by block, so the
// porosity is the same bits for any thread count.
void Coupler::porosity_range(const Particles& p, int t, std::size_t b, std::size_t e) {
  for (std::size_t q = b; q < e; q += kParticleBlock) {
    sums_.begin_block(t);
    const std::size_t q1 = std::min(e, q + kParticleBlock);
    for (std::size_t i = q; i < q1; ++i) {
      VolumeShares sh;
      particle_volume_shares(grid_, p.x[i], p.y[i], p.radius[i], sh);
      for (int c = 0; c < sh.count; ++c) sums_.add(t, sh.cell[c], sh.volume[c], 0.0);
    }
  }
}

const std::vector<double>& Coupler::finish_porosity(double time) {
  std::fill(solid_.begin(), solid_.end(), 0.0);
  sums_.add_to(solid_, nullptr);
  porosity_from_solid(grid_, solid_, eps_);
  for (std::size_t c = 0; c < eps_.size(); ++c) {
    if (!(eps_[c] > 0.0 && eps_[c] <= 1.0 + 1e-12)) {
      std::ostringstream os;
      os << "porosity " << eps_[c] << " outside (0, 1] in gas cell (" << c % grid_.nx << ", "
         << c / grid_.nx << ") at t = " << time << " s: particles overlap too much";
      throw SimulationFailure(os.str());
    }
  }
  return eps_;
}

const std::vector<double>& Coupler::exchange(const Particles& p, double time,
                                             std::vector<double>& fx, std::vector<double>& fy,
                                             double& total_x, double& total_y,
                                             const std::vector<std::size_t>& split) {
  for (int t = 0; t < sums_.threads(); ++t) {
    sums_.clear(t);
    drag_sums_.clear(t);
  }
  per_thread(p.size(), split, [&](int t, std::size_t b, std::size_t e) {
    porosity_range(p, t, b, e);
    drag_sums_range(t, b, e);
  });
  const std::vector<double>& eps = finish_porosity(time);
  finish_interaction_force(fx, fy, total_x, total_y);
  return eps;
}

void Coupler::refresh_cells(const GasSolver& gas) {
  const int cells = grid_.cells();
  for (int c = 0; c < cells; ++c) {
    gas.cell_velocity(c, cell_ux_[c], cell_uy_[c]);
    gas.pressure_gradient(c, cell_gx_[c], cell_gy_[c]);
    ln_eps_[c] = std::log(eps_[c]);
  }
}

void Coupler::freeze_drag(Particles& p, const std::vector<std::size_t>& split) {
  per_thread(p.size(), split, [&](int, std::size_t b, std::size_t e) { freeze_range(p, b, e); });
}

void Coupler::freeze_range(Particles& p, std::size_t begin, std::size_t end) {
  constexpr double kPi = std::numbers::pi;
  // Three passes over the range: the gas at each particle (gathers from the cells), the drag
  // coefficient (pure arithmetic over arrays: vectorised), the forces.
  for (std::size_t i = begin; i < end; ++i) {
    const int c = grid_.cell_of(p.x[i], p.y[i]);
    cell_[i] = c;
    gas_ux_[i] = cell_ux_[c];
    gas_uy_[i] = cell_uy_[c];
    const double sx = cell_ux_[c] - p.vx[i], sy = cell_uy_[c] - p.vy[i];
    slip_x_[i] = sx;
    slip_y_[i] = sy;
    slip_[i] = std::sqrt(sx * sx + sy * sy);
    eps_at_[i] = eps_[c];
    ln_eps_at_[i] = ln_eps_[c];
  }
  const std::size_t count = end - begin;
  di_felice_beta_many(count, p.radius.data() + begin, eps_at_.data() + begin,
                      ln_eps_at_.data() + begin, slip_.data() + begin, rho_f_, mu_f_,
                      beta_.data() + begin);
  const bool pgf = pressure_gradient_force_;
  for (std::size_t i = begin; i < end; ++i) {
    const int c = cell_[i];
    drag_x_[i] = beta_[i] * slip_x_[i];
    drag_y_[i] = beta_[i] * slip_y_[i];
    double bx = 0.0, by = 0.0;
    if (pgf) {
      const double R = p.radius[i];
      const double v = 4.0 / 3.0 * kPi * R * R * R;
      bx = -(v * cell_gx_[c]);
      by = -(v * cell_gy_[c]);
    }
    base_fx_[i] = bx;
    base_fy_[i] = by;
    // drag + (-(V g)) is drag - V g to the last bit; without model A the drag alone.
    p.ext_fx[i] = pgf ? drag_x_[i] + bx : drag_x_[i];
    p.ext_fy[i] = pgf ? drag_y_[i] + by : drag_y_[i];
  }
}

void Coupler::advance_drag(Particles& p, bool update, const std::vector<std::size_t>& split) {
  count_step();
  per_thread(p.size(), split,
             [&](int, std::size_t b, std::size_t e) { advance_drag_range(p, update, b, e); });
}

void Coupler::advance_drag_range(Particles& p, bool update, std::size_t b, std::size_t e) {
  double* sx = sum_x_.data();
  double* sy = sum_y_.data();
  double* dx = drag_x_.data();
  double* dy = drag_y_.data();
  for (std::size_t i = b; i < e; ++i) {
    sx[i] += dx[i];
    sy[i] += dy[i];
  }
  if (!update) return;
  const double* beta = beta_.data();
  const double* ux = gas_ux_.data();
  const double* uy = gas_uy_.data();
  const double* bx = base_fx_.data();
  const double* by = base_fy_.data();
  const double* vx = p.vx.data();
  const double* vy = p.vy.data();
  double* fx = p.ext_fx.data();
  double* fy = p.ext_fy.data();
  if (pressure_gradient_force_) {
    for (std::size_t i = b; i < e; ++i) {
      dx[i] = beta[i] * (ux[i] - vx[i]);
      dy[i] = beta[i] * (uy[i] - vy[i]);
      fx[i] = dx[i] + bx[i];
      fy[i] = dy[i] + by[i];
    }
  } else {
    for (std::size_t i = b; i < e; ++i) {
      fx[i] = dx[i] = beta[i] * (ux[i] - vx[i]);
      fy[i] = dy[i] = beta[i] * (uy[i] - vy[i]);
    }
  }
}

void Coupler::take_interaction_force(std::vector<double>& fx, std::vector<double>& fy,
                                     double& total_x, double& total_y,
                                     const std::vector<std::size_t>& split) {
  for (int t = 0; t < drag_sums_.threads(); ++t) drag_sums_.clear(t);
  per_thread(cell_.size(), split,
             [&](int t, std::size_t b, std::size_t e) { drag_sums_range(t, b, e); });
  finish_interaction_force(fx, fy, total_x, total_y);
}

// Each particle's summed drag into its frozen cell, block by block (the same bits for any
// thread count), then the particle sums reset.
void Coupler::drag_sums_range(int t, std::size_t b, std::size_t e) {
  for (std::size_t q = b; q < e; q += kParticleBlock) {
    drag_sums_.begin_block(t);
    const std::size_t q1 = std::min(e, q + kParticleBlock);
    for (std::size_t i = q; i < q1; ++i) drag_sums_.add(t, cell_[i], sum_x_[i], sum_y_[i]);
  }
  for (std::size_t i = b; i < e; ++i) sum_x_[i] = sum_y_[i] = 0.0;
}

void Coupler::finish_interaction_force(std::vector<double>& fx, std::vector<double>& fy,
                                       double& total_x, double& total_y) {
  std::fill(cell_sum_x_.begin(), cell_sum_x_.end(), 0.0);
  std::fill(cell_sum_y_.begin(), cell_sum_y_.end(), 0.0);
  drag_sums_.add_to(cell_sum_x_, &cell_sum_y_);
  const std::size_t cells = cell_sum_x_.size();
  fx.resize(cells);
  fy.resize(cells);
  const double scale = accumulated_ > 0 ? 1.0 / (accumulated_ * grid_.cell_volume()) : 0.0;
  total_x = total_y = 0.0;
  for (std::size_t c = 0; c < cells; ++c) {
    fx[c] = cell_sum_x_[c] * scale;  // eq 21
    fy[c] = cell_sum_y_[c] * scale;
    total_x += cell_sum_x_[c];
    total_y += cell_sum_y_[c];
  }
  if (accumulated_ > 0) {
    total_x /= accumulated_;
    total_y /= accumulated_;
  }
  accumulated_ = 0;
}

void Coupler::save(CouplingState& out) const {
  out.eps = eps_;
  out.cell = cell_;
  out.beta = beta_;
  out.gas_ux = gas_ux_;
  out.gas_uy = gas_uy_;
  out.base_fx = base_fx_;
  out.base_fy = base_fy_;
  out.drag_x = drag_x_;
  out.drag_y = drag_y_;
  out.sum_x = sum_x_;
  out.sum_y = sum_y_;
  out.accumulated = accumulated_;
}

void Coupler::restore(const CouplingState& in, std::size_t particles) {
  const auto cells = static_cast<std::size_t>(grid_.cells());
  bool fits = in.eps.size() == cells && in.cell.size() == particles;
  for (const auto* v : {&in.beta, &in.gas_ux, &in.gas_uy, &in.base_fx, &in.base_fy, &in.drag_x,
                        &in.drag_y, &in.sum_x, &in.sum_y})
    fits = fits && v->size() == particles;
  if (!fits)
    throw InputError("state file's coupling block does not fit this scene's grid or particles");
  for (int c : in.cell)
    if (c < 0 || c >= grid_.cells()) throw InputError("state file's coupling block is inconsistent");
  eps_ = in.eps;
  cell_ = in.cell;
  beta_ = in.beta;
  gas_ux_ = in.gas_ux;
  gas_uy_ = in.gas_uy;
  base_fx_ = in.base_fx;
  base_fy_ = in.base_fy;
  drag_x_ = in.drag_x;
  drag_y_ = in.drag_y;
  sum_x_ = in.sum_x;
  sum_y_ = in.sum_y;
  accumulated_ = in.accumulated;
}

}  // namespace fluidbed
