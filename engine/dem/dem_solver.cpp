#include "dem/dem_solver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/threads.hpp"

namespace fluidbed {

Integrator parse_integrator(const std::string& name) {
  if (name == "newmark") return Integrator::Newmark;
  if (name == "velocity_verlet") return Integrator::VelocityVerlet;
  if (name == "symplectic_euler") return Integrator::SymplecticEuler;
  throw InputError("time.integrator: unknown integrator \"" + name + "\"");
}

DemSolver::DemSolver(const Settings& s, Particles particles)
    : walls_(slab_walls(s.domain)),
      integrator_(parse_integrator(s.time.integrator)),
      incremental_(s.contact.displacement == "incremental"),
      frozen_(s.particles.frozen),
      dt_(s.time.dt),
      gravity_(s.physics.gravity),
      width_(s.domain.width),
      height_(s.domain.height),
      overlap_limit_(s.diagnostics.overlap_limit) {
  params_.kn = s.contact.stiffness;
  params_.kt = s.contact.stiffness * s.contact.tangential_stiffness_ratio;
  params_.eta_n = s.contact.damping;
  params_.eta_t = s.contact.damping * s.contact.tangential_damping_ratio;
  params_.mu = s.contact.friction;

  const std::size_t n = particles.size();
  threads_ = resolve_threads(s.threads);
  // A fork costs a few microseconds: worth it only when a step has real work.
  parallel_ = threads_ > 1 && n >= 256;
  double dmax = 0.0;
  for (double r : particles.radius) dmax = std::max(dmax, 2.0 * r);
  list_.configure(width_, height_, dmax, s.contact.skin * dmax, n);
  state_.particles = std::move(particles);
  overlap_.assign(n, 0.0);
  state_.walls.resize(n, static_cast<int>(walls_.size()));
  // Newmark and Verlet carry the last acceleration; at rest with no contacts it is gravity.
  auto& p = state_.particles;
  for (std::size_t i = 0; i < n; ++i) {
    p.ax[i] = p.ext_fx[i] * p.inv_mass[i];
    p.ay[i] = p.ext_fy[i] * p.inv_mass[i] - gravity_;
  }
}

void DemSolver::set_state(DemState s) {
  if (s.particles.size() != state_.particles.size())
    throw InputError("state has " + std::to_string(s.particles.size()) +
                     " particles but the scene has " + std::to_string(state_.particles.size()));
  if (s.walls.walls != static_cast<int>(walls_.size()))
    throw InputError("state was saved with " + std::to_string(s.walls.walls) +
                     " walls but the scene has " + std::to_string(walls_.size()));
  state_ = std::move(s);
  list_.import_history(state_.pairs);
  list_.build(state_.particles);
  state_.pairs.clear();
}

DemState DemSolver::exported_state() const {
  DemState copy = state_;
  list_.export_history(copy.pairs);
  return copy;
}

void DemSolver::fail(const std::string& what) const {
  std::ostringstream os;
  os.precision(6);
  os << what << " at t = " << state_.time << " s (step " << state_.step << ")";
  throw SimulationFailure(os.str());
}

template <class F>
void DemSolver::for_particles(F&& f) {
  const auto n = static_cast<std::int64_t>(state_.particles.size());
#pragma omp parallel for schedule(static) num_threads(threads_) if (parallel_)
  for (std::int64_t i = 0; i < n; ++i) f(static_cast<std::size_t>(i));
}

template <bool Incremental>
void DemSolver::evaluate_forces(double dtau) {
  Particles& P = state_.particles;
  const auto n = static_cast<std::int64_t>(P.size());
  const double* x = P.x.data();
  const double* y = P.y.data();
  const double* vx = P.vx.data();
  const double* vy = P.vy.data();
  const double* w = P.w.data();
  const double* r = P.radius.data();

  PhaseClock clock(times_);
  if (list_.stale(P)) list_.build(P);
  clock.lap(Phase::Neighbours);

  // Pass 1, over candidate pairs: each pair's force from its history, written to its slot.
  NeighbourList& L = list_;
  const auto m = static_cast<std::int64_t>(L.size());
  const std::int32_t* li = L.i.data();
  const std::int32_t* lj = L.j.data();
  double* ldn = L.dn.data();
  double* ldt = L.dt.data();
  std::uint8_t* touch = L.touching.data();
  double* lfx = L.fx.data();
  double* lfy = L.fy.data();
  double* lft = L.ft.data();
  double* lratio = L.ratio.data();
  const ContactParams params = params_;
  int contacts = 0, sliding = 0;
  double max_ratio = 0.0;
#pragma omp parallel for schedule(static) num_threads(threads_) if (parallel_) \
    reduction(+ : contacts, sliding) reduction(max : max_ratio)
  for (std::int64_t k = 0; k < m; ++k) {
    const int i = li[k], j = lj[k];
    const double px = x[j] - x[i], py = y[j] - y[i];
    const double R = r[i] + r[j];
    const double L2 = px * px + py * py;
    if (L2 >= R * R || L2 <= 0.0) {  // apart (coincident centres are caught as an overlap)
      touch[k] = 0;
      ldn[k] = ldt[k] = 0.0;
      lfx[k] = lfy[k] = lft[k] = 0.0;
      lratio[k] = L2 <= 0.0 ? 1.0 : 0.0;
      max_ratio = std::max(max_ratio, lratio[k]);
      continue;
    }
    const double Lc = std::sqrt(L2);
    const double nx = px / Lc, ny = py / Lc;
    const double tx = -ny, ty = nx;
    const double vrx = vx[i] - vx[j], vry = vy[i] - vy[j];
    const double vn = vrx * nx + vry * ny;
    const double vt = vrx * tx + vry * ty + w[i] * r[i] + w[j] * r[j];
    double dn = ldn[k], dt = ldt[k], tau = dtau;
    if (!touch[k]) {
      dn = dt = 0.0;
      if (Incremental) tau = std::min(time_since_touch(px, py, -vrx, -vry, R, Lc), dtau);  // eq 13
    }
    if constexpr (Incremental) {
      dn += vn * tau;  // eqs 14, 16
    } else {
      dn = R - Lc;
    }
    dt += vt * tau;  // eqs 15, 17
    const ContactForce f = contact_force(params, dn, dt, vn, vt);
    touch[k] = 1;
    ldn[k] = dn;
    ldt[k] = dt;
    lfx[k] = f.fn * nx + f.ft * tx;
    lfy[k] = f.fn * ny + f.ft * ty;
    lft[k] = f.ft;
    lratio[k] = 1.0 - Lc / R;
    max_ratio = std::max(max_ratio, lratio[k]);
    ++contacts;
    sliding += f.sliding;
  }

  // Pass 2, over particles: gravity, gas, the pair forces gathered in a fixed order (entries
  // where the particle is second, then first), and the walls.
  const std::int32_t* fb = L.first_begin.data();
  const std::int32_t* sb = L.second_begin.data();
  const std::int32_t* sp = L.second_pair.data();
  WallHistory& wh = state_.walls;
  const int nw = static_cast<int>(walls_.size());
  const Wall* walls = walls_.data();
  double* fx = P.fx.data();
  double* fy = P.fy.data();
  double* tq = P.torque.data();
  double* ov = overlap_.data();
  const double g = gravity_;
  double max_wall_ratio = 0.0;
  int wall_contacts = 0;
#pragma omp parallel for schedule(static) num_threads(threads_) if (parallel_) \
    reduction(+ : wall_contacts, sliding) reduction(max : max_wall_ratio)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    double fxi = P.ext_fx[i], fyi = P.ext_fy[i] - P.mass[i] * g, tqi = 0.0, ovi = 0.0;
    for (std::int32_t q = sb[i]; q < sb[i + 1]; ++q) {
      const std::int32_t k = sp[q];
      fxi -= lfx[k];
      fyi -= lfy[k];
      tqi += r[i] * lft[k];
      ovi = std::max(ovi, lratio[k]);
    }
    for (std::int32_t k = fb[i]; k < fb[i + 1]; ++k) {
      fxi += lfx[k];
      fyi += lfy[k];
      tqi += r[i] * lft[k];
      ovi = std::max(ovi, lratio[k]);
    }
    for (int c = 0; c < nw; ++c) {
      const Wall& wall = walls[c];
      const std::size_t s = i * nw + c;
      const double d = wall.nx * x[i] + wall.ny * y[i] - wall.offset;
      if (d >= r[i]) {
        wh.active[s] = 0;
        wh.dn[s] = 0.0;
        wh.dt[s] = 0.0;
        continue;
      }
      const double overlap = r[i] - d;
      const double nx = -wall.nx, ny = -wall.ny;  // from the particle into the wall
      const double tx = -ny, ty = nx;
      const double vn = vx[i] * nx + vy[i] * ny;
      const double vt = vx[i] * tx + vy[i] * ty + w[i] * r[i];
      double dn = wh.dn[s], dt = wh.dt[s], tau = dtau;
      if (!wh.active[s] && Incremental) tau = std::min(time_since_touch_wall(overlap, vn), dtau);
      if constexpr (Incremental) {
        dn += vn * tau;
      } else {
        dn = overlap;
      }
      dt += vt * tau;
      const ContactForce f = contact_force(params, dn, dt, vn, vt);
      wh.active[s] = 1;
      wh.dn[s] = dn;
      wh.dt[s] = dt;
      fxi += f.fn * nx + f.ft * tx;
      fyi += f.fn * ny + f.ft * ty;
      tqi += r[i] * f.ft;
      ++wall_contacts;
      sliding += f.sliding;
      max_wall_ratio = std::max(max_wall_ratio, overlap / r[i]);
      ovi = std::max(ovi, 0.5 * overlap / r[i]);
    }
    fx[i] = fxi;
    fy[i] = fyi;
    tq[i] = tqi;
    ov[i] = ovi;
  }
  clock.lap(Phase::Contacts);

  diag_.max_overlap_ratio = max_ratio;
  diag_.max_wall_overlap_ratio = max_wall_ratio;
  diag_.pair_contacts = contacts;
  diag_.wall_contacts = wall_contacts;
  diag_.sliding_contacts = sliding;
  if (max_ratio > overlap_limit_) {
    // The first pair (in list order) with the largest overlap, for the message.
    for (std::int64_t k = 0; k < m; ++k)
      if (lratio[k] == max_ratio) {
        worst_pair_i_ = li[k];
        worst_pair_j_ = lj[k];
        break;
      }
  }
}

void DemSolver::evaluate_forces_dispatch(double dtau) {
  times_.add(Phase::Integration, PhaseTimes::Clock::now() - integration_start_);
  if (incremental_) {
    evaluate_forces<true>(dtau);
  } else {
    evaluate_forces<false>(dtau);
  }
  integration_start_ = PhaseTimes::Clock::now();
}

void DemSolver::step() {
  Particles& P = state_.particles;
  const double h = dt_;
  integration_start_ = PhaseTimes::Clock::now();
  if (frozen_) {  // a fixed bed: the clock runs, nothing moves
    std::fill(P.vx.begin(), P.vx.end(), 0.0);
    std::fill(P.vy.begin(), P.vy.end(), 0.0);
    std::fill(P.w.begin(), P.w.end(), 0.0);
    state_.time = static_cast<double>(++state_.step) * dt_;
    diag_.kinetic_energy = 0.0;
    return;
  }
  switch (integrator_) {
    case Integrator::Newmark: {
      // Eqs 24-28 with alpha = 1/2, beta = 1/4: predict, evaluate forces at the prediction,
      // correct with the new acceleration.
      const double hh4 = 0.25 * h * h;
      for_particles([&](std::size_t i) {
        P.x[i] += h * P.vx[i] + hh4 * P.ax[i];
        P.y[i] += h * P.vy[i] + hh4 * P.ay[i];
        P.vx[i] += 0.5 * h * P.ax[i];
        P.vy[i] += 0.5 * h * P.ay[i];
        P.w[i] += 0.5 * h * P.aw[i];
      });
      evaluate_forces_dispatch(h);
      for_particles([&](std::size_t i) {
        const double ax = P.fx[i] * P.inv_mass[i], ay = P.fy[i] * P.inv_mass[i];
        const double aw = P.torque[i] * P.inv_inertia[i];
        P.vx[i] += 0.5 * h * ax;
        P.vy[i] += 0.5 * h * ay;
        P.w[i] += 0.5 * h * aw;
        P.x[i] += hh4 * ax;
        P.y[i] += hh4 * ay;
        P.ax[i] = ax;
        P.ay[i] = ay;
        P.aw[i] = aw;
      });
      break;
    }
    case Integrator::VelocityVerlet: {
      // Kick half, drift, forces with the half-step velocity, kick half.
      for_particles([&](std::size_t i) {
        P.vx[i] += 0.5 * h * P.ax[i];
        P.vy[i] += 0.5 * h * P.ay[i];
        P.w[i] += 0.5 * h * P.aw[i];
        P.x[i] += h * P.vx[i];
        P.y[i] += h * P.vy[i];
      });
      evaluate_forces_dispatch(h);
      for_particles([&](std::size_t i) {
        P.ax[i] = P.fx[i] * P.inv_mass[i];
        P.ay[i] = P.fy[i] * P.inv_mass[i];
        P.aw[i] = P.torque[i] * P.inv_inertia[i];
        P.vx[i] += 0.5 * h * P.ax[i];
        P.vy[i] += 0.5 * h * P.ay[i];
        P.w[i] += 0.5 * h * P.aw[i];
      });
      break;
    }
    case Integrator::SymplecticEuler: {
      evaluate_forces_dispatch(h);
      for_particles([&](std::size_t i) {
        P.ax[i] = P.fx[i] * P.inv_mass[i];
        P.ay[i] = P.fy[i] * P.inv_mass[i];
        P.aw[i] = P.torque[i] * P.inv_inertia[i];
        P.vx[i] += h * P.ax[i];
        P.vy[i] += h * P.ay[i];
        P.w[i] += h * P.aw[i];
        P.x[i] += h * P.vx[i];
        P.y[i] += h * P.vy[i];
      });
      break;
    }
  }
  state_.time = static_cast<double>(++state_.step) * dt_;
  finish_step();
  times_.add(Phase::Integration, PhaseTimes::Clock::now() - integration_start_);
}

void DemSolver::finish_step() {
  const Particles& P = state_.particles;
  const std::size_t n = P.size();
  double ke = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double inertia = 1.0 / P.inv_inertia[i];
    ke += 0.5 * P.mass[i] * (P.vx[i] * P.vx[i] + P.vy[i] * P.vy[i]) +
          0.5 * inertia * P.w[i] * P.w[i];
  }
  diag_.kinetic_energy = ke;
  if (!std::isfinite(ke)) {
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(P.vx[i] + P.vy[i] + P.w[i] + P.x[i] + P.y[i]))
        fail("particle " + std::to_string(i) + " has a non-finite position or velocity (NaN)");
    fail("kinetic energy is not finite");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double r = P.radius[i];
    const char* where = nullptr;
    if (!std::isfinite(P.x[i] + P.y[i])) where = "has a non-finite position (NaN)";
    else if (P.x[i] < -r) where = "left the bed through the left wall";
    else if (P.x[i] > width_ + r) where = "left the bed through the right wall";
    else if (P.y[i] < -r) where = "left the bed through the bottom wall";
    else if (P.y[i] > height_ + r) where = "left the bed through the top";
    if (where) fail("particle " + std::to_string(i) + " " + where);
  }
  const double worst = std::max(diag_.max_overlap_ratio, 0.5 * diag_.max_wall_overlap_ratio);
  if (worst > overlap_limit_) {
    std::ostringstream os;
    os.precision(3);
    if (diag_.max_overlap_ratio >= 0.5 * diag_.max_wall_overlap_ratio)
      os << "runaway overlap: particles " << worst_pair_i_ << " and " << worst_pair_j_
         << " overlap by " << 100.0 * diag_.max_overlap_ratio << " % of their radii sum";
    else
      os << "runaway overlap: a particle overlaps a wall by " << 100.0 * diag_.max_wall_overlap_ratio
         << " % of its radius";
    os << " (limit " << 100.0 * overlap_limit_ << " %, diagnostics.overlap_limit)";
    fail(os.str());
  }
}

std::uint64_t DemSolver::state_hash() const {
  Fnv1a h;
  h.value(state_.time);
  h.value(state_.step);
  h.value(configuration_hash());
  return h.digest();
}

std::uint64_t DemSolver::configuration_hash() const {
  Fnv1a h;
  const Particles& P = state_.particles;
  for (const auto* v : {&P.x, &P.y, &P.vx, &P.vy, &P.w, &P.ax, &P.ay, &P.aw}) h.values(*v);
  // The touching pairs in (i, j) order: the same whatever the skin or the rebuild times.
  const NeighbourList& L = list_;
  for (std::size_t k = 0; k < L.size(); ++k) {
    if (!L.touching[k]) continue;
    h.value(L.i[k]);
    h.value(L.j[k]);
    h.value(L.dn[k]);
    h.value(L.dt[k]);
  }
  h.values(state_.walls.active);
  h.values(state_.walls.dn);
  h.values(state_.walls.dt);
  return h.digest();
}

}  // namespace fluidbed
