#include "dem/dem_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/threads.hpp"
#include "dem/block_ledger.hpp"
#include "dem/pair_kernel.hpp"

namespace fluidbed {

DemSolver::DemSolver(const DemParams& d, Particles particles)
    : walls_(d.walls),
      params_(d.contact),
      wall_params_(d.contact),
      integrator_(d.integrator),
      incremental_(d.incremental),
      frozen_(d.frozen),
      dt_(d.dt),
      gravity_(d.gravity),
      width_(d.width),
      height_(d.height),
      thickness_(d.thickness),
      overlap_limit_(d.overlap_limit),
      renumber_steps_(d.renumber_steps) {
  wall_params_.mu = d.wall_mu.value_or(d.contact.mu);
  depth_ = particles.has_depth();
  if (params_.hertz && !depth_)  // the monolayer's passes have the linear law only
    throw InputError(
        "contact.law = \"hertz_mindlin\" needs a thick slab: domain.thickness above "
        "particles.diameter");
  for (std::size_t c = 0; c < walls_.size(); ++c) {
    const Wall& w = walls_[c];
    (w.nz == 0.0 ? planar_walls_ : depth_walls_).push_back(static_cast<int>(c));
    wall_nx_.push_back(w.nx);
    wall_ny_.push_back(w.ny);
    wall_nz_.push_back(w.nz);
    wall_offset_.push_back(w.offset);
  }
  if (depth_walls_.size() > kDepthWalls)
    throw std::logic_error("DemSolver: more than a front and a back wall");
  const std::size_t n = particles.size();
  threads_ = resolve_threads(d.threads);
  // A fork costs a microsecond or two: worth it only when a step has real work.
  parallel_ = threads_ > 1 && n >= 256;
  partial_.assign(static_cast<std::size_t>(threads_), StepPartial{});
  passed_.assign(static_cast<std::size_t>(threads_), {});
  passed_depth_.assign(static_cast<std::size_t>(threads_), {});
  if (depth_) {
    wall_chunks_.assign(static_cast<std::size_t>(threads_), {});
    for (WallChunk& c : wall_chunks_) {
      c.on.resize(kWallChunk);
      c.particle.resize(kWallChunk);
      c.out.resize(kWallChunk, true);
    }
  }
  busy_.assign(static_cast<std::size_t>(threads_), ThreadClock{});
  block_ke_.assign(particle_blocks(n), 0.0);
  block_ledger_.assign(particle_blocks(n), EnergyLedger{});
  double dmax = 0.0;
  for (double r : particles.radius) dmax = std::max(dmax, 2.0 * r);
  skin_ = d.skin * dmax;
  list_.configure(width_, height_, dmax, skin_, n, threads_, depth_);
  // The renumbering's cells: a diameter (not the skin, on which no result may depend), and no
  // more than about twice the particles, as the neighbour list's.
  const double per_particle = width_ * height_ / static_cast<double>(std::max<std::size_t>(n, 1));
  cell_ = std::max(dmax, std::sqrt(0.5 * per_particle));
  near_wall_.assign(static_cast<std::size_t>(threads_), {});
  state_.particles = std::move(particles);
  overlap_.assign(n, 0.0);
  state_.walls.resize(n, static_cast<int>(walls_.size()), depth_);
  // Newmark and Verlet carry the last acceleration; at rest with no contacts it is gravity.
  auto& p = state_.particles;
  for (std::size_t i = 0; i < n; ++i) {
    p.ax[i] = p.ext_fx[i] * p.inv_mass[i];
    p.ay[i] = p.ext_fy[i] * p.inv_mass[i] - gravity_;
    if (depth_) p.az[i] = p.ext_fz[i] * p.inv_mass[i];
  }
}

void DemSolver::fail(const std::string& what) const {
  std::ostringstream os;
  os.precision(6);
  os << what << " at t = " << state_.time << " s (step " << state_.step << ")";
  throw SimulationFailure(os.str());
}

// Pass 1 over this thread's candidate pairs [k0, k1) (those whose first particle is in its range
// [b, e)): the contact law of the touching ones. In three sweeps, so that none branches on
// whether a pair touches (in no order a predictor could learn) and the arithmetic runs several
// pairs at a time (dem/pair_kernel.hpp): which pairs touch; the touching slots listed; the
// contact law of those into a compact scratch (kept for the particle pass), their history back
// to the slots. A contact whose second particle belongs to a later thread is passed to it.
template <bool Incremental>
void DemSolver::pair_pass(int t, std::size_t e, double dtau, StepPartial& acc) {
  const Particles& P = state_.particles;
  const auto a = P.arrays();
  const PairKernelParticles pk{a.x, a.y, a.vx, a.vy, a.w, a.radius};
  NeighbourList& L = list_;
  PairSlots& S = L.slots();
  const std::int64_t k0 = acc.k0, k1 = S.first_begin[e];
  const std::int32_t* li = S.i.data();
  const std::int32_t* lj = S.j.data();
  double* ldn = S.dn.data();
  double* lds = S.ds.data();
  std::uint8_t* touch = S.touching.data();
  std::uint8_t* code = L.code.data() + k0;
  classify_pairs(pk, li, lj, k0, k1, code);
  // The touching pairs of this range: their slots, negated (~k) for those that touch for the
  // first time, whose history starts from zero (scratch: each thread writes its own range).
  // Coincident centres are no contact but an overlap of 1 (rare: a branch).
  std::int32_t* on = L.active.data() + k0;
  double max_ratio = 0.0;
  std::int64_t worst = -1;
  const std::int64_t count = list_touching(code, touch, k0, k1, on, max_ratio, worst,
                                           [&](std::int64_t k) { ldn[k] = lds[k] = 0.0; });
  ContactScratch& cs = L.contact_scratch;
  const PairContactOut out{cs.dn.data() + k0,      cs.ds.data() + k0,       cs.fx.data() + k0,
                           cs.fy.data() + k0,      cs.ft.data() + k0,       cs.ratio.data() + k0,
                           cs.dashpot.data() + k0, cs.friction.data() + k0, cs.sliding.data() + k0};
  pair_contacts({pk, li, lj, ldn, lds, on, count, params_, Incremental, dtau}, out);
  // Rolling resistance (contact.rolling_friction): a torque per contact, and its loss as friction.
  const bool rolling = params_.mu_r > 0.0;
  double* roll = cs.roll.data() + k0;
  if (rolling) {
    const double* r = a.radius;
    const double* w = a.w;
    const double* inv_i = a.inv_inertia;
    for (std::int64_t q = 0; q < count; ++q) {
      const std::int32_t k = listed_slot(on[q]);
      const std::int32_t i = li[k], j = lj[k];
      const double w_rel = w[i] - w[j];
      roll[q] =
          rolling_torque(params_.mu_r, r[i] * r[j] / (r[i] + r[j]),
                         params_.kn * std::max(out.dn[q], 0.0), w_rel, inv_i[i] + inv_i[j], dtau);
      out.friction[q] += std::fabs(roll[q]) * std::fabs(w_rel) * dtau;
    }
  }
  int sliding = 0;
  std::vector<Push>& pass = passed_[static_cast<std::size_t>(t)];
  pass.clear();
  const auto end = static_cast<std::int32_t>(e);
  BlockLedger ledger(block_ledger_.data());  // by the pairs' first particles: they come in i order
  for (std::int64_t q = 0; q < count; ++q) {
    const std::int32_t k = listed_slot(on[q]);
    ldn[k] = out.dn[q];
    lds[k] = out.ds[q];
    const double ratio = out.ratio[q];
    worst = ratio > max_ratio ? k : worst;
    max_ratio = std::max(max_ratio, ratio);
    sliding += out.sliding[q];
    ledger.add(static_cast<std::size_t>(li[k]), 0.0, ContactLoss{out.dashpot[q], out.friction[q]});
    if (lj[k] >= end)
      pass.push_back(Push{out.fx[q], out.fy[q], out.ft[q], ratio, lj[k], rolling ? roll[q] : 0.0});
  }
  acc.contacts = static_cast<int>(count);
  acc.sliding += sliding;
  acc.max_ratio = std::max(acc.max_ratio, max_ratio);
  acc.worst = worst;
}

// Pass 2 over particles [b, e), after every thread's pair pass. Each particle's force is summed
// in a fixed order whatever the thread count: gas and gravity; its contacts in (i, j) order of
// their slots - those passed on by earlier threads (their first particle below b), then this
// thread's, a contact adding its force to i and subtracting it from j, so a particle gets those
// where it is second by ascending partner, then those where it is first, by ascending partner -
// then walls 0, 1, 2, (3) for the particles that can reach one. Then the integrator's part after
// the forces, each block's kinetic energy and the box check, and on the way each block's share of
// the gas's work over the step at the velocities the contacts see. Returns true when a particle
// has left the box.
template <bool Incremental>
bool DemSolver::particle_pass(int t, std::size_t b, std::size_t e, double dtau, StepPartial& acc) {
  Particles& P = state_.particles;
  const auto a = P.arrays();
  const double *x = a.x, *y = a.y, *vx = a.vx, *vy = a.vy, *w = a.w, *r = a.radius;
  double *fx = a.fx, *fy = a.fy, *tq = a.torque, *ov = overlap_.data();
  const double* efx = a.ext_fx;
  const double* efy = a.ext_fy;
  const double* m = a.mass;
  const double g = gravity_;
  for (std::size_t blk = b / kParticleBlock; blk * kParticleBlock < e; ++blk) {
    const std::size_t i0 = std::max(b, blk * kParticleBlock),
                      i1 = std::min(e, (blk + 1) * kParticleBlock);
    double gas = 0.0;
    for (std::size_t i = i0; i < i1; ++i) {
      fx[i] = efx[i];
      fy[i] = efy[i] - m[i] * g;
      tq[i] = 0.0;
      ov[i] = 0.0;
      gas += efx[i] * vx[i] + efy[i] * vy[i];
    }
    block_ledger_[blk].gas_work += gas * dtau;
  }
  auto take = [&](std::int32_t j, double cfx, double cfy, double cft, double ratio) {
    fx[j] -= cfx;
    fy[j] -= cfy;
    tq[j] += r[j] * cft;
    ov[j] = std::max(ov[j], ratio);
  };
  const auto lo = static_cast<std::int32_t>(b), hi = static_cast<std::int32_t>(e);
  for (int u = 0; u < t; ++u)
    for (const Push& c : passed_[static_cast<std::size_t>(u)])
      if (c.j >= lo && c.j < hi) take(c.j, c.fx, c.fy, c.ft, c.ratio);
  {
    const NeighbourList& L = list_;
    const PairSlots& S = L.slots();
    const std::int32_t* li = S.i.data();
    const std::int32_t* lj = S.j.data();
    const std::int32_t* on = L.active.data() + acc.k0;
    const ContactScratch& cs = L.contact_scratch;
    const double* cfx = cs.fx.data() + acc.k0;
    const double* cfy = cs.fy.data() + acc.k0;
    const double* cft = cs.ft.data() + acc.k0;
    const double* crt = cs.ratio.data() + acc.k0;
    for (int q = 0; q < acc.contacts; ++q) {
      const std::int32_t k = listed_slot(on[q]);
      const std::int32_t i = li[k], j = lj[k];
      fx[i] += cfx[q];
      fy[i] += cfy[q];
      tq[i] += r[i] * cft[q];
      ov[i] = std::max(ov[i], crt[q]);
      if (j < hi) take(j, cfx[q], cfy[q], cft[q], crt[q]);
    }
    // Rolling resistance torques, in the same order of contacts as the forces above.
    if (params_.mu_r > 0.0) {
      for (int u = 0; u < t; ++u)
        for (const Push& c : passed_[static_cast<std::size_t>(u)])
          if (c.j >= lo && c.j < hi) tq[c.j] -= c.roll;
      const double* roll = cs.roll.data() + acc.k0;
      for (int q = 0; q < acc.contacts; ++q) {
        const std::int32_t k = listed_slot(on[q]);
        tq[li[k]] += roll[q];
        if (lj[k] < hi) tq[lj[k]] -= roll[q];
      }
    }
  }
  // Walls: only the particles that can reach one before the next neighbour-list build (listed at
  // each build, ascending).
  WallHistory& wh = state_.walls;
  const int nw = static_cast<int>(walls_.size());
  const ContactParams params = wall_params_;
  std::uint8_t* active = wh.active.data();
  double* hdn = wh.dn.data();
  double* hds = wh.ds.data();
  double max_wall_ratio = 0.0;
  int wall_contacts = 0, sliding = 0;
  BlockLedger ledger(block_ledger_.data());
  for (const std::int32_t ni : near_wall_[static_cast<std::size_t>(t)]) {
    const auto i = static_cast<std::size_t>(ni);
    for (int c = 0; c < nw; ++c) {
      const Wall& wall = walls_[static_cast<std::size_t>(c)];
      const std::size_t s = i * nw + c;
      const double d = wall.nx * x[i] + wall.ny * y[i] - wall.offset;
      if (!(d < r[i])) {  // apart: a contact that has just ended leaves no history
        if (active[s]) {
          active[s] = 0;
          hdn[s] = hds[s] = 0.0;
        }
        continue;
      }
      const bool fresh = !active[s];
      active[s] = 1;
      const double nx = -wall.nx, ny = -wall.ny;  // from the particle into the wall
      const double tx = -ny, ty = nx;
      const double overlap = r[i] - d;
      const double vn = vx[i] * nx + vy[i] * ny;
      const double vt = vx[i] * tx + vy[i] * ty + w[i] * r[i];
      double dn = hdn[s], ds = hds[s], tau = dtau;
      if (fresh && Incremental) tau = std::min(time_since_touch_wall(overlap, vn), dtau);
      if constexpr (Incremental) {
        dn += vn * tau;
      } else {
        dn = overlap;
      }
      ds += vt * tau;
      const double ds_before = ds;
      const ContactForce f = contact_force(params, dn, ds, vn, vt);
      ContactLoss loss = contact_loss(params, f, ds_before, ds, vn, vt, dtau);
      double roll = 0.0;
      if (params.mu_r > 0.0) {
        roll = rolling_torque(params.mu_r, r[i], params.kn * std::max(dn, 0.0), w[i],
                              a.inv_inertia[i], dtau);
        loss.friction += std::fabs(roll) * std::fabs(w[i]) * dtau;
      }
      ledger.add(i, 0.0, loss);
      hdn[s] = dn;
      hds[s] = ds;
      fx[i] += f.fn * nx + f.ft * tx;
      fy[i] += f.fn * ny + f.ft * ty;
      tq[i] += r[i] * f.ft;
      if (params.mu_r > 0.0) tq[i] += roll;
      sliding += f.sliding;
      max_wall_ratio = std::max(max_wall_ratio, overlap / r[i]);
      ov[i] = std::max(ov[i], 0.5 * overlap / r[i]);
      ++wall_contacts;
    }
  }
  return finish_particle_pass(b, e, wall_contacts, sliding, max_wall_ratio, acc);
}

bool DemSolver::finish_particle_pass(std::size_t b, std::size_t e, int wall_contacts, int sliding,
                                     double max_wall_ratio, StepPartial& acc) {
  bool outside = false;
  for (std::size_t blk = b / kParticleBlock; blk * kParticleBlock < e; ++blk)
    outside |= after_forces(blk, std::max(b, blk * kParticleBlock),
                            std::min(e, (blk + 1) * kParticleBlock));
  acc.wall_contacts += wall_contacts;
  acc.sliding += sliding;
  acc.max_wall_ratio = std::max(acc.max_wall_ratio, max_wall_ratio);
  return outside;
}

// The integrator's part before the forces (predictor, kick-drift) for particles [b, e).
void DemSolver::before_forces(std::size_t b, std::size_t e) {
  predict(integrator_, dt_, state_.particles, b, e);
}

// The integrator's part after the forces (corrector, kick, Euler update) for particles [i0, i1)
// of block blk, and the block's kinetic energy. Returns true when one of them has left the box.
bool DemSolver::after_forces(std::size_t blk, std::size_t i0, std::size_t i1) {
  correct(integrator_, dt_, state_.particles, i0, i1);
  const auto a = std::as_const(state_.particles).arrays();
  const double *x = a.x, *y = a.y, *vx = a.vx, *vy = a.vy, *w = a.w;
  const double *ii = a.inv_inertia, *m = a.mass, *r = a.radius;
  double ke = 0.0;
  for (std::size_t i = i0; i < i1; ++i)
    ke += 0.5 * m[i] * (vx[i] * vx[i] + vy[i] * vy[i]) + 0.5 * w[i] * w[i] / ii[i];
  if (depth_) {
    const Particles& P = state_.particles;
    for (std::size_t i = i0; i < i1; ++i)
      ke += 0.5 * m[i] * P.vz[i] * P.vz[i] + 0.5 * (P.wx[i] * P.wx[i] + P.wy[i] * P.wy[i]) / ii[i];
  }
  block_ke_[blk] = ke;
  // Every particle inside the box (with a radius of slack): branch-free; finish_step looks for
  // the culprit only when this fails.
  bool outside = false;
  for (std::size_t i = i0; i < i1; ++i)
    outside |= !(x[i] >= -r[i] && x[i] <= width_ + r[i] && y[i] >= -r[i] && y[i] <= height_ + r[i]);
  if (depth_) {
    const double* z = state_.particles.z.data();
    for (std::size_t i = i0; i < i1; ++i) outside |= !(z[i] >= -r[i] && z[i] <= thickness_ + r[i]);
  }
  return outside;
}

void DemSolver::rebuild(int t, int T, std::size_t b, std::size_t e) {
  list_.build(state_.particles, t, T, b, e);
  find_near_wall(near_wall_[static_cast<std::size_t>(t)], b, e);
  if (t == 0) near_threads_ = T;
}

void DemSolver::find_near_wall(std::vector<std::int32_t>& out, std::size_t b, std::size_t e) const {
  const Particles& P = state_.particles;
  const int nw = static_cast<int>(walls_.size());
  const std::uint8_t* active = state_.walls.active.data();
  out.clear();
  for (std::size_t i = b; i < e; ++i) {
    bool near = false;
    for (const int c : planar_walls_) {
      const Wall& wall = walls_[static_cast<std::size_t>(c)];
      const double d = wall.nx * P.x[i] + wall.ny * P.y[i] - wall.offset;
      near = near || d < P.radius[i] + skin_ || active[i * nw + c] != 0;
    }
    if (near) out.push_back(static_cast<std::int32_t>(i));
  }
}

void DemSolver::thread_range(int t, int T, std::size_t& b, std::size_t& e) const {
  split_particles(split_, state_.particles.size(), t, T, b, e);
}

void DemSolver::balance(int T) {
  // Whole blocks per thread, cut where each thread's share of the work matches its speed: a
  // candidate pair costs about one unit, a particle's own work (integration, gathering, walls)
  // about three (measured on the packing's split). A bed is denser at the bottom, so equal
  // particle counts would leave the thread with the upper half waiting for the other; and two
  // cores need not be equally fast (on a virtual machine one may share its core with another
  // guest: measured 1.6 times slower on a streaming loop), so each thread's speed is measured -
  // its work units over the time it spent on its own particles since the last balance - and
  // smoothed. The split changes the speed only: every result is the same bits for any split.
  constexpr double kParticleWork = 3.0;
  const std::size_t n = state_.particles.size();
  const std::size_t blocks = particle_blocks(n);
  const std::int32_t* fb = list_.slots().first_begin.data();
  const bool have_list = list_.built();
  auto work_to = [&](std::size_t p) {  // work of particles [0, p)
    return kParticleWork * static_cast<double>(p) + (have_list ? static_cast<double>(fb[p]) : 0.0);
  };
  const auto nT = static_cast<std::size_t>(T);
  if (speed_.size() != nT) {
    speed_.assign(nT, 1.0);
    work_.assign(nT, 0.0);
  } else if (steps_since_balance_ > 0) {
    for (std::size_t t = 0; t < nT; ++t) {
      const double busy = busy_[t].seconds;
      if (busy > 0.0 && work_[t] > 0.0)
        speed_[t] =
            0.5 * speed_[t] + 0.5 * work_[t] * static_cast<double>(steps_since_balance_) / busy;
    }
  }
  double speed_sum = 0.0;
  for (double v : speed_) speed_sum += v;
  const double total = work_to(n);
  split_.assign(nT + 1, n);
  split_[0] = 0;
  std::size_t blk = 0;
  double ahead = 0.0;  // speed of the threads before t
  for (std::size_t t = 1; t < nT; ++t) {
    ahead += speed_[t - 1];
    const double target = total * ahead / speed_sum;
    while (blk < blocks && work_to(std::min(n, (blk + 1) * kParticleBlock)) <= target) ++blk;
    split_[t] = std::max(split_[t - 1], std::min(n, blk * kParticleBlock));
  }
  for (std::size_t t = 0; t < nT; ++t) {
    work_[t] = work_to(split_[t + 1]) - work_to(split_[t]);
    busy_[t].seconds = 0.0;
  }
  steps_since_balance_ = 0;
}

template <bool Incremental>
void DemSolver::step_particles(const RangeWork& after) {
  const double h = dt_;
  for (auto& a : partial_) a = StepPartial{};
    // One parallel region per step: every loop over particles uses the same block split, so each
    // particle's arrays stay in one core's cache (on a 2-core VM a loop that moves them to the
    // other core costs more than it saves); the pairs are split where the particles are.
#pragma omp parallel num_threads(threads_) if (parallel_)
  {
    int t = 0, T = 1;
    this_thread(t, T);
    std::size_t b = 0, e = 0;
    thread_range(t, T, b, e);
    auto last = PhaseTimes::Clock::now();
    auto lap = [&](Phase phase) {  // thread 0 keeps the split (after barriers: wall time)
      if (t != 0) return;
      const auto now = PhaseTimes::Clock::now();
      times_.add(phase, now - last);
      last = now;
    };
    // Each thread's time on its own particles, for balance().
    double& busy = busy_[static_cast<std::size_t>(t)].seconds;
    auto since = [](PhaseTimes::Clock::time_point from) {
      return std::chrono::duration<double>(PhaseTimes::Clock::now() - from).count();
    };
    auto start = PhaseTimes::Clock::now();
    before_forces(b, e);
    list_.displacement(state_.particles, b, e, partial_[t].moved2);
    busy += since(start);
    lap(Phase::Integration);
#pragma omp barrier
    // Every thread reads the same partial results in the same order: the same decision.
    double m1 = 0.0, m2 = 0.0;
    for (const auto& a : partial_) {
      m2 = std::max(std::max(m2, a.moved2[1]), std::min(m1, a.moved2[0]));
      m1 = std::max(m1, a.moved2[0]);
    }
    if (list_.stale(m1, m2) || near_threads_ != T) {
#pragma omp single
      balance(T);
      thread_range(t, T, b, e);
      rebuild(t, T, b, e);
    }
    lap(Phase::Neighbours);
    for (std::size_t blk = b / kParticleBlock; blk * kParticleBlock < e; ++blk)
      block_ledger_[blk] = EnergyLedger{};
    partial_[t].k0 = list_.slots().first_begin[b];
    start = PhaseTimes::Clock::now();
    if (depth_) {
      pair_pass_depth(t, e, h, Incremental, partial_[t]);
    } else {
      pair_pass<Incremental>(t, e, h, partial_[t]);
    }
    busy += since(start);
#pragma omp barrier
    start = PhaseTimes::Clock::now();
    partial_[t].outside = depth_ ? particle_pass_depth(t, b, e, h, Incremental, partial_[t])
                                 : particle_pass<Incremental>(t, b, e, h, partial_[t]);
    busy += since(start);
    lap(Phase::Contacts);
    if (after) {
      after(b, e);
      lap(Phase::Coupling);
    }
  }
  ++steps_since_balance_;
  StepPartial sum;
  for (const auto& a : partial_) {
    sum.outside = sum.outside || a.outside;
    sum.contacts += a.contacts;  // pairs
    sum.sliding += a.sliding;
    sum.wall_contacts += a.wall_contacts;
    sum.max_ratio = std::max(sum.max_ratio, a.max_ratio);
    sum.max_wall_ratio = std::max(sum.max_wall_ratio, a.max_wall_ratio);
  }
  diag_.max_overlap_ratio = sum.max_ratio;
  diag_.max_wall_overlap_ratio = sum.max_wall_ratio;
  diag_.pair_contacts = sum.contacts;
  diag_.wall_contacts = sum.wall_contacts;
  diag_.sliding_contacts = sum.sliding;
  double ke = 0.0;
  for (double k : block_ke_) ke += k;
  diag_.kinetic_energy = ke;
  EnergyLedger step_ledger;
  for (const EnergyLedger& l : block_ledger_) step_ledger += l;
  ledger_ += step_ledger;
  outside_ = sum.outside;
}

void DemSolver::step(const RangeWork& after) {
  Particles& P = state_.particles;
  if (frozen_) {  // a fixed bed: the clock runs, nothing moves
    std::fill(P.vx.begin(), P.vx.end(), 0.0);
    std::fill(P.vy.begin(), P.vy.end(), 0.0);
    std::fill(P.w.begin(), P.w.end(), 0.0);
    for (auto* v : {&P.vz, &P.wx, &P.wy}) std::fill(v->begin(), v->end(), 0.0);
    state_.time = static_cast<double>(++state_.step) * dt_;
    diag_.kinetic_energy = 0.0;
    if (after) after(0, P.size());
    return;
  }
  if (renumber_steps_ > 0 && state_.step % renumber_steps_ == 0) {
    PhaseClock clock(times_);
    renumber();
    clock.lap(Phase::Neighbours);
  }
  if (incremental_) {
    step_particles<true>(after);
  } else {
    step_particles<false>(after);
  }
  state_.time = static_cast<double>(++state_.step) * dt_;
  PhaseClock clock(times_);
  finish_step();
  clock.lap(Phase::Integration);
}

void DemSolver::finish_step() {
  const Particles& P = state_.particles;
  const std::size_t n = P.size();
  if (!std::isfinite(diag_.kinetic_energy)) {
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(P.vx[i] + P.vy[i] + P.w[i] + P.x[i] + P.y[i]) ||
          (depth_ && !std::isfinite(P.z[i] + P.vz[i] + P.wx[i] + P.wy[i])))
        fail("particle " + std::to_string(id_of(i)) +
             " has a non-finite position or velocity (NaN)");
    fail("kinetic energy is not finite");
  }
  const double* x = P.x.data();
  const double* y = P.y.data();
  const double* r = P.radius.data();
  if (outside_) {
    for (std::size_t i = 0; i < n; ++i) {
      const char* where = nullptr;
      if (!std::isfinite(x[i] + y[i]))
        where = "has a non-finite position (NaN)";
      else if (x[i] < -r[i])
        where = "left the bed through the left wall";
      else if (x[i] > width_ + r[i])
        where = "left the bed through the right wall";
      else if (y[i] < -r[i])
        where = "left the bed through the bottom wall";
      else if (y[i] > height_ + r[i])
        where = "left the bed through the top";
      else if (depth_ && !std::isfinite(P.z[i]))
        where = "has a non-finite position (NaN)";
      else if (depth_ && P.z[i] < -r[i])
        where = "left the bed through the front wall";
      else if (depth_ && P.z[i] > thickness_ + r[i])
        where = "left the bed through the back wall";
      if (where) fail("particle " + std::to_string(id_of(i)) + " " + where);
    }
  }
  const double worst = std::max(diag_.max_overlap_ratio, 0.5 * diag_.max_wall_overlap_ratio);
  if (worst > overlap_limit_) {
    // The first pair (in list order) with the largest overlap, for the message.
    for (const auto& a : partial_)
      if (a.worst >= 0 && a.max_ratio == diag_.max_overlap_ratio) {
        const auto k = static_cast<std::size_t>(a.worst);
        const std::size_t i = id_of(static_cast<std::size_t>(list_.slots().i[k]));
        const std::size_t j = id_of(static_cast<std::size_t>(list_.slots().j[k]));
        worst_pair_i_ = static_cast<int>(std::min(i, j));
        worst_pair_j_ = static_cast<int>(std::max(i, j));
        break;
      }
    std::ostringstream os;
    os.precision(3);
    if (diag_.max_overlap_ratio >= 0.5 * diag_.max_wall_overlap_ratio)
      os << "runaway overlap: particles " << worst_pair_i_ << " and " << worst_pair_j_
         << " overlap by " << 100.0 * diag_.max_overlap_ratio << " % of their radii sum";
    else
      os << "runaway overlap: a particle overlaps a wall by "
         << 100.0 * diag_.max_wall_overlap_ratio << " % of its radius";
    os << " (limit " << 100.0 * overlap_limit_ << " %, diagnostics.overlap_limit)";
    fail(os.str());
  }
}

SpringEnergy DemSolver::spring_energy() const {
  SpringEnergy e;
  const double kn = params_.kn, kt = params_.kt;
  const std::vector<double>& r = state_.particles.radius;
  // ds2: the shear displacement squared (a thick slab's is a vector); r_eff: the contact's R*
  // (Hertz-Mindlin only: its normal spring stores (2/5) k dn^2 with k = hertz_kn sqrt(R* dn), its
  // tangential one (1/2) k_t ds^2 at the current overlap).
  auto add = [&](double dn, double ds2, double r_eff) {
    const double c = std::max(dn, 0.0);  // the normal spring acts in compression only (eq 3)
    if (params_.hertz) {
      const double a = std::sqrt(r_eff * c);
      e.normal += 0.4 * params_.hertz_kn * a * c * c;
      e.tangential += 0.5 * params_.hertz_kt * a * ds2;
    } else {
      e.normal += 0.5 * kn * c * c;
      e.tangential += 0.5 * kt * ds2;
    }
  };
  auto sq = [&](const std::vector<double>& ds, const std::vector<double>& ds_y,
                const std::vector<double>& ds_z, std::size_t k) {
    return ds[k] * ds[k] + (depth_ ? ds_y[k] * ds_y[k] + ds_z[k] * ds_z[k] : 0.0);
  };
  const PairSlots& S = list_.slots();
  for (std::size_t k = 0; k < S.size(); ++k)
    if (S.touching[k]) {
      const double ri = r[static_cast<std::size_t>(S.i[k])],
                   rj = r[static_cast<std::size_t>(S.j[k])];
      add(S.dn[k], sq(S.ds, S.ds_y, S.ds_z, k), ri * rj / (ri + rj));
    }
  const WallHistory& wh = state_.walls;
  const std::size_t nw = std::max<std::size_t>(walls_.size(), 1);
  for (std::size_t s = 0; s < wh.active.size(); ++s)
    if (wh.active[s]) add(wh.dn[s], sq(wh.ds, wh.ds_y, wh.ds_z, s), r[s / nw]);
  return e;
}

std::uint64_t DemSolver::state_hash() const {
  Fnv1a h;
  h.value(state_.time);
  h.value(state_.step);
  h.value(configuration_hash());
  return h.digest();
}

}  // namespace fluidbed
