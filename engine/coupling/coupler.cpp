#include "coupling/coupler.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cfd/gas_solver.hpp"
#include "core/errors.hpp"
#include "core/threads.hpp"
#include "coupling/drag.hpp"
#include "coupling/porosity.hpp"

namespace fluidbed {

Coupler::Coupler(const GasGrid& grid, const Settings& s, std::size_t particles)
    : grid_(grid),
      rho_f_(s.gas.density),
      mu_f_(s.gas.viscosity),
      pressure_gradient_force_(s.coupling.pressure_gradient_force),
      solid_(static_cast<std::size_t>(grid.cells()), 0.0),
      eps_(static_cast<std::size_t>(grid.cells()), 1.0),
      drag_x_(particles, 0.0),
      drag_y_(particles, 0.0),
      cell_(particles, 0),
      sum_fx_(static_cast<std::size_t>(grid.cells()), 0.0),
      sum_fy_(static_cast<std::size_t>(grid.cells()), 0.0) {
  threads_ = resolve_threads(s.threads);
  parallel_ = threads_ > 1 && particles >= 256;
  shares_.resize(particles);
  const auto cells = static_cast<std::size_t>(grid.cells());
  for (auto* v : {&cell_ux_, &cell_uy_, &cell_gx_, &cell_gy_, &ln_eps_}) v->assign(cells, 0.0);
}

const std::vector<double>& Coupler::compute_porosity(const Particles& p, double time) {
  // Each sphere's shares in parallel (the closed forms are the work), then added up per cell in
  // particle order, so the porosity is the same bits for any thread count.
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if (parallel_)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    particle_volume_shares(grid_, p.x[i], p.y[i], p.radius[i], shares_[i]);
  }
  std::fill(solid_.begin(), solid_.end(), 0.0);
  for (const VolumeShares& sh : shares_)
    for (int q = 0; q < sh.count; ++q) solid_[sh.cell[q]] += sh.volume[q];
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

void Coupler::refresh_cells(const GasSolver& gas) {
  const int cells = grid_.cells();
  for (int c = 0; c < cells; ++c) {
    gas.cell_velocity(c, cell_ux_[c], cell_uy_[c]);
    gas.pressure_gradient(c, cell_gx_[c], cell_gy_[c]);
    ln_eps_[c] = std::log(eps_[c]);
  }
}

void Coupler::compute_fluid_forces(Particles& p) {
  constexpr double kPi = 3.14159265358979323846;
  const auto n = static_cast<std::int64_t>(p.size());
  const bool pgf = pressure_gradient_force_;
#pragma omp parallel for schedule(static) num_threads(threads_) if (parallel_)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const int c = grid_.cell_of(p.x[i], p.y[i]);
    cell_[i] = c;
    const double R = p.radius[i];
    const double sx = cell_ux_[c] - p.vx[i], sy = cell_uy_[c] - p.vy[i];
    const double beta = di_felice_beta_ln(R, rho_f_, mu_f_, eps_[c], ln_eps_[c],
                                          std::sqrt(sx * sx + sy * sy));
    drag_x_[i] = beta * sx;
    drag_y_[i] = beta * sy;
    double fx = drag_x_[i], fy = drag_y_[i];
    if (pgf) {
      const double v = 4.0 / 3.0 * kPi * R * R * R;
      fx -= v * cell_gx_[c];
      fy -= v * cell_gy_[c];
    }
    p.ext_fx[i] = fx;
    p.ext_fy[i] = fy;
  }
}

void Coupler::accumulate_drag(const Particles& p) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    sum_fx_[cell_[i]] += drag_x_[i];
    sum_fy_[cell_[i]] += drag_y_[i];
  }
  ++accumulated_;
}

void Coupler::take_interaction_force(std::vector<double>& fx, std::vector<double>& fy,
                                     double& total_x, double& total_y) {
  const std::size_t n = sum_fx_.size();
  fx.resize(n);
  fy.resize(n);
  const double scale = accumulated_ > 0 ? 1.0 / (accumulated_ * grid_.cell_volume()) : 0.0;
  total_x = total_y = 0.0;
  for (std::size_t c = 0; c < n; ++c) {
    fx[c] = sum_fx_[c] * scale;  // eq 21
    fy[c] = sum_fy_[c] * scale;
    total_x += sum_fx_[c];
    total_y += sum_fy_[c];
    sum_fx_[c] = sum_fy_[c] = 0.0;
  }
  if (accumulated_ > 0) {
    total_x /= accumulated_;
    total_y /= accumulated_;
  }
  accumulated_ = 0;
}

void Coupler::save(CouplingState& out) const {
  out.eps = eps_;
  out.drag_x = drag_x_;
  out.drag_y = drag_y_;
  out.sum_fx = sum_fx_;
  out.sum_fy = sum_fy_;
  out.cell = cell_;
  out.accumulated = accumulated_;
}

void Coupler::restore(const CouplingState& in, std::size_t particles) {
  const auto cells = static_cast<std::size_t>(grid_.cells());
  if (in.eps.size() != cells || in.sum_fx.size() != cells || in.sum_fy.size() != cells ||
      in.drag_x.size() != particles || in.drag_y.size() != particles || in.cell.size() != particles)
    throw InputError("state file's coupling block does not fit this scene's grid or particles");
  for (int c : in.cell)
    if (c < 0 || c >= grid_.cells()) throw InputError("state file's coupling block is inconsistent");
  eps_ = in.eps;
  drag_x_ = in.drag_x;
  drag_y_ = in.drag_y;
  sum_fx_ = in.sum_fx;
  sum_fy_ = in.sum_fy;
  cell_ = in.cell;
  accumulated_ = in.accumulated;
}

}  // namespace fluidbed
