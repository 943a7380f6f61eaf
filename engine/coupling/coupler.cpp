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
      solid_(static_cast<std::size_t>(grid.cells()), 0.0) {
  if (c.smoothing_length > 0.0) smoother_.emplace(grid, c.smoothing_length);
  s_.eps.assign(static_cast<std::size_t>(grid.cells()), 1.0);
  s_.cell.assign(particles, 0);
  threads_ = resolve_threads(c.threads);
  parallel_ = threads_ > 1 && particles >= 256;
  sums_.configure(grid.cells(), threads_);
  geometry_.resize(static_cast<std::size_t>(threads_));
  for (ShareGeometry& g : geometry_) g.resize(kChunk);
  freeze_scratch_.resize(static_cast<std::size_t>(threads_));
  for (FreezeScratch& f : freeze_scratch_)
    for (auto* v : {&f.slip_x, &f.slip_y, &f.slip, &f.eps_at, &f.ln_eps_at}) v->assign(kChunk, 0.0);
  drag_sums_.configure(grid.cells(), threads_);
  for (auto* v : {&s_.gas_ux, &s_.gas_uy, &s_.beta, &s_.base_fx, &s_.base_fy, &s_.drag_x,
                  &s_.drag_y, &s_.sum_x, &s_.sum_y})
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
// porosity is the same bits for any thread count. The geometry is found a chunk at a time.
void Coupler::porosity_range(const Particles& p, int t, std::size_t b, std::size_t e) {
  ShareGeometry& geo = geometry_[static_cast<std::size_t>(t)];
  for (std::size_t c0 = b; c0 < e; c0 += kChunk) {
    const std::size_t c1 = std::min(e, c0 + kChunk);
    share_geometry(grid_, c1 - c0, p.x.data() + c0, p.y.data() + c0, p.radius.data() + c0, geo);
    for (std::size_t q = c0; q < c1; q += kParticleBlock) {
      sums_.begin_block(t);
      const std::size_t q1 = std::min(c1, q + kParticleBlock);
      for (std::size_t i = q; i < q1; ++i) {
        VolumeShares sh;
        shares_from_geometry(grid_, geo, i - c0, p.radius[i], sh);
        for (int c = 0; c < sh.count; ++c) sums_.add(t, sh.cell[c], sh.volume[c], 0.0);
      }
    }
  }
}

const std::vector<double>& Coupler::finish_porosity(double time) {
  std::fill(solid_.begin(), solid_.end(), 0.0);
  sums_.add_to(solid_, nullptr);
  if (smoother_) smoother_->apply(solid_);
  porosity_from_solid(grid_, solid_, s_.eps);
  for (std::size_t c = 0; c < s_.eps.size(); ++c) {
    if (!(s_.eps[c] > 0.0 && s_.eps[c] <= 1.0 + 1e-12)) {
      std::ostringstream os;
      os << "porosity " << s_.eps[c] << " outside (0, 1] in gas cell (" << c % grid_.nx << ", "
         << c / grid_.nx << ") at t = " << time << " s: particles overlap too much";
      throw SimulationFailure(os.str());
    }
  }
  return s_.eps;
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
    ln_eps_[c] = std::log(s_.eps[c]);
  }
}

void Coupler::freeze_drag(Particles& p, const std::vector<std::size_t>& split) {
  per_thread(p.size(), split,
             [&](int t, std::size_t b, std::size_t e) { freeze_range(p, t, b, e); });
}

void Coupler::freeze_range(Particles& p, int t, std::size_t b, std::size_t e) {
  FreezeScratch& f = freeze_scratch_[static_cast<std::size_t>(t)];
  for (std::size_t c0 = b; c0 < e; c0 += kChunk)
    freeze_chunk(p, f, c0, std::min(e, c0 + kChunk));
}

void Coupler::freeze_chunk(Particles& p, FreezeScratch& f, std::size_t begin, std::size_t end) {
  constexpr double kPi = std::numbers::pi;
  // Three passes over the chunk: the gas at each particle (gathers from the cells), the drag
  // coefficient (pure arithmetic over arrays: vectorised), the forces.
  const double dx = grid_.dx(), dy = grid_.dy(), bottom = grid_.bottom;
  const int nx = grid_.nx, ny = grid_.ny;
  const bool depth = p.has_depth();
  double* slip_x = f.slip_x.data();  // indexed by i - begin
  double* slip_y = f.slip_y.data();
  double* slip = f.slip.data();
  double* eps_at = f.eps_at.data();
  double* ln_eps_at = f.ln_eps_at.data();
  for (std::size_t i = begin; i < end; ++i) {
    const std::size_t k = i - begin;
    const int c = GasGrid::along(p.y[i] - bottom, dy, ny) * nx + GasGrid::along(p.x[i], dx, nx);
    s_.cell[i] = c;
    s_.gas_ux[i] = cell_ux_[c];
    s_.gas_uy[i] = cell_uy_[c];
    const double sx = cell_ux_[c] - p.vx[i], sy = cell_uy_[c] - p.vy[i];
    slip_x[k] = sx;
    slip_y[k] = sy;
    // A thick slab's particle also slips through the gas along z, which has no z velocity.
    const double sz = depth ? -p.vz[i] : 0.0;
    slip[k] = std::sqrt(sx * sx + sy * sy + sz * sz);
    eps_at[k] = s_.eps[c];
    ln_eps_at[k] = ln_eps_[c];
  }
  di_felice_beta_many(end - begin, p.radius.data() + begin, eps_at, ln_eps_at, slip, rho_f_, mu_f_,
                      s_.beta.data() + begin);
  const bool pgf = pressure_gradient_force_;
  for (std::size_t i = begin; i < end; ++i) {
    const std::size_t k = i - begin;
    const int c = s_.cell[i];
    s_.drag_x[i] = s_.beta[i] * slip_x[k];
    s_.drag_y[i] = s_.beta[i] * slip_y[k];
    // Without model A the base force is -0.0, which added to any drag gives the drag itself.
    double bx = -0.0, by = -0.0;
    if (pgf) {
      const double R = p.radius[i];
      const double v = 4.0 / 3.0 * kPi * R * R * R;
      bx = -(v * cell_gx_[c]);
      by = -(v * cell_gy_[c]);
    }
    s_.base_fx[i] = bx;
    s_.base_fy[i] = by;
    // drag + (-(V g)) is drag - V g to the last bit.
    p.ext_fx[i] = s_.drag_x[i] + bx;
    p.ext_fy[i] = s_.drag_y[i] + by;
  }
  // Along z the drag alone, beta (0 - v_z): the gas is one cell deep with no z velocity and no
  // pressure gradient across the slab; its reaction goes to the front and back walls, not the gas.
  if (depth)
    for (std::size_t i = begin; i < end; ++i) p.ext_fz[i] = -(s_.beta[i] * p.vz[i]);
}

void Coupler::advance_drag(Particles& p, bool update, const std::vector<std::size_t>& split) {
  count_step();
  per_thread(p.size(), split,
             [&](int, std::size_t b, std::size_t e) { advance_drag_range(p, update, b, e); });
}

void Coupler::advance_drag_range(Particles& p, bool update, std::size_t b, std::size_t e) {
  double* sx = s_.sum_x.data();
  double* sy = s_.sum_y.data();
  double* dx = s_.drag_x.data();
  double* dy = s_.drag_y.data();
  for (std::size_t i = b; i < e; ++i) {
    sx[i] += dx[i];
    sy[i] += dy[i];
  }
  if (!update) return;
  const double* beta = s_.beta.data();
  const double* ux = s_.gas_ux.data();
  const double* uy = s_.gas_uy.data();
  const double* bx = s_.base_fx.data();
  const double* by = s_.base_fy.data();
  const double* vx = p.vx.data();
  const double* vy = p.vy.data();
  double* fx = p.ext_fx.data();
  double* fy = p.ext_fy.data();
  for (std::size_t i = b; i < e; ++i) {
    dx[i] = beta[i] * (ux[i] - vx[i]);
    dy[i] = beta[i] * (uy[i] - vy[i]);
    fx[i] = dx[i] + bx[i];
    fy[i] = dy[i] + by[i];
  }
  if (p.has_depth())
    for (std::size_t i = b; i < e; ++i) p.ext_fz[i] = -(beta[i] * p.vz[i]);
}

void Coupler::take_interaction_force(std::vector<double>& fx, std::vector<double>& fy,
                                     double& total_x, double& total_y,
                                     const std::vector<std::size_t>& split) {
  for (int t = 0; t < drag_sums_.threads(); ++t) drag_sums_.clear(t);
  per_thread(s_.cell.size(), split,
             [&](int t, std::size_t b, std::size_t e) { drag_sums_range(t, b, e); });
  finish_interaction_force(fx, fy, total_x, total_y);
}

// Each particle's summed drag into its frozen cell, block by block (the same bits for any
// thread count), then the particle sums reset.
void Coupler::drag_sums_range(int t, std::size_t b, std::size_t e) {
  for (std::size_t q = b; q < e; q += kParticleBlock) {
    drag_sums_.begin_block(t);
    const std::size_t q1 = std::min(e, q + kParticleBlock);
    for (std::size_t i = q; i < q1; ++i) drag_sums_.add(t, s_.cell[i], s_.sum_x[i], s_.sum_y[i]);
  }
  for (std::size_t i = b; i < e; ++i) s_.sum_x[i] = s_.sum_y[i] = 0.0;
}

void Coupler::finish_interaction_force(std::vector<double>& fx, std::vector<double>& fy,
                                       double& total_x, double& total_y) {
  std::fill(cell_sum_x_.begin(), cell_sum_x_.end(), 0.0);
  std::fill(cell_sum_y_.begin(), cell_sum_y_.end(), 0.0);
  drag_sums_.add_to(cell_sum_x_, &cell_sum_y_);
  const std::size_t cells = cell_sum_x_.size();
  fx.resize(cells);
  fy.resize(cells);
  const double scale = s_.accumulated > 0 ? 1.0 / (s_.accumulated * grid_.cell_volume()) : 0.0;
  total_x = total_y = 0.0;
  for (std::size_t c = 0; c < cells; ++c) {
    fx[c] = cell_sum_x_[c] * scale;  // eq 21
    fy[c] = cell_sum_y_[c] * scale;
    total_x += cell_sum_x_[c];
    total_y += cell_sum_y_[c];
  }
  if (s_.accumulated > 0) {
    total_x /= s_.accumulated;
    total_y /= s_.accumulated;
  }
  s_.accumulated = 0;
}

void Coupler::save(CouplingState& out) const { out = s_; }

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
  s_ = in;
}

}  // namespace fluidbed
