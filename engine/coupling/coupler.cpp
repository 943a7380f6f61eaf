#include "coupling/coupler.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cfd/gas_solver.hpp"
#include "core/errors.hpp"
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
      sum_fy_(static_cast<std::size_t>(grid.cells()), 0.0) {}

const std::vector<double>& Coupler::compute_porosity(const Particles& p, double time) {
  std::fill(solid_.begin(), solid_.end(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) add_particle_volume(grid_, p.x[i], p.y[i], p.radius[i], solid_);
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

void Coupler::compute_fluid_forces(Particles& p, const GasSolver& gas) {
  constexpr double kPi = 3.14159265358979323846;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int c = grid_.cell_of(p.x[i], p.y[i]);
    cell_[i] = c;
    double ux, uy;
    gas.cell_velocity(c, ux, uy);
    const double R = p.radius[i];
    const DragForce f = di_felice_drag(R, rho_f_, mu_f_, eps_[c], ux, uy, p.vx[i], p.vy[i]);
    drag_x_[i] = f.fx;
    drag_y_[i] = f.fy;
    double fx = f.fx, fy = f.fy;
    if (pressure_gradient_force_) {
      double gx, gy;
      gas.pressure_gradient(c, gx, gy);
      const double v = 4.0 / 3.0 * kPi * R * R * R;
      fx -= v * gx;
      fy -= v * gy;
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
