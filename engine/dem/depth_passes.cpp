// The particle step's two force passes for a thick slab, where particles move in three
// dimensions: the same structure as the monolayer's (DemSolver::pair_pass, particle_pass, with
// the same order of summation, so that results are the same bits for any thread count), with the
// contact law of contact_force_3d and the front and back walls as real contacts. Scalar loops:
// the monolayer's vectorised kernels are left as they are.
#include <algorithm>
#include <cmath>

#include "core/threads.hpp"
#include "dem/block_ledger.hpp"
#include "dem/dem_solver.hpp"

namespace fluidbed {

namespace {

// Rolling resistance in three dimensions (rolling_torque along the relative spin): the torque on
// i against w_rel = w_i - w_j, limited as rolling_torque is.
Vec3 rolling_torque_3d(double mu_r, double r_roll, double fn_spring, const Vec3& w_rel,
                       double inv_inertia_sum, double h) {
  const double spin = std::sqrt(dot(w_rel, w_rel));
  if (spin <= 0.0) return {};
  const double m = rolling_torque(mu_r, r_roll, fn_spring, spin, inv_inertia_sum, h);  // <= 0
  return (m / spin) * w_rel;
}

// One step of a contact whose history is entry k of h (the pair slots or the wall history: dn,
// ds, ds_y, ds_z): contact_force_3d from the history's shear vector, the new history written back.
template <class History>
ContactForce3 advance_contact(History& h, std::size_t k, const ContactParams& params, double dn,
                              const Vec3& n, const Vec3& vr, double tau, double dtau) {
  Vec3 shear{h.ds[k], h.ds_y[k], h.ds_z[k]};
  const ContactForce3 f = contact_force_3d(params, dn, shear, n, vr, tau, dtau);
  h.dn[k] = dn;
  h.ds[k] = shear.x;
  h.ds_y[k] = shear.y;
  h.ds_z[k] = shear.z;
  return f;
}

}  // namespace

void DemSolver::pair_pass_depth(int t, std::size_t e, double dtau, bool incremental,
                                StepPartial& acc) {
  const Particles& P = state_.particles;
  const double *x = P.x.data(), *y = P.y.data(), *z = P.z.data();
  const double *vx = P.vx.data(), *vy = P.vy.data(), *vz = P.vz.data();
  const double *wx = P.wx.data(), *wy = P.wy.data(), *wz = P.w.data();
  const double *r = P.radius.data(), *inv_i = P.inv_inertia.data();
  NeighbourList& L = list_;
  PairSlots& S = L.slots();
  const std::int64_t k0 = acc.k0, k1 = S.first_begin[e];
  std::int32_t* on = L.active.data() + k0;
  ContactScratch& cs = L.contact_scratch;
  const bool rolling = params_.mu_r > 0.0;
  std::int64_t count = 0;
  double max_ratio = 0.0;
  std::int64_t worst = -1;
  int sliding = 0;
  std::vector<Push>& pass = passed_[static_cast<std::size_t>(t)];
  std::vector<PushDepth>& pass_depth = passed_depth_[static_cast<std::size_t>(t)];
  pass.clear();
  pass_depth.clear();
  const auto end = static_cast<std::int32_t>(e);
  BlockLedger ledger(block_ledger_.data());  // by the pairs' first particles: they come in i order
  for (std::int64_t k = k0; k < k1; ++k) {
    const std::int32_t i = S.i[k], j = S.j[k];
    const Vec3 p{x[j] - x[i], y[j] - y[i], z[j] - z[i]};
    const double R = r[i] + r[j];
    const double L2 = dot(p, p);
    if (L2 <= 0.0) {  // coincident centres: no contact, but an overlap of 1
      if (1.0 > max_ratio) {
        max_ratio = 1.0;
        worst = k;
      }
      S.touching[k] = 0;
      continue;
    }
    if (!(L2 < R * R)) {
      S.touching[k] = 0;
      continue;
    }
    const bool fresh = !S.touching[k];
    if (fresh) S.dn[k] = S.ds[k] = S.ds_y[k] = S.ds_z[k] = 0.0;
    S.touching[k] = 1;
    const double Lc = std::sqrt(L2);
    const Vec3 n = (1.0 / Lc) * p;
    const Vec3 spin = r[i] * Vec3{wx[i], wy[i], wz[i]} + r[j] * Vec3{wx[j], wy[j], wz[j]};
    const Vec3 v_rel{vx[i] - vx[j], vy[i] - vy[j], vz[i] - vz[j]};
    const Vec3 vr = v_rel + cross(spin, n);
    double tau = dtau;
    if (fresh && incremental)
      tau = std::min(time_since_touch(p.x, p.y, -v_rel.x, -v_rel.y, R, Lc, p.z, -v_rel.z), dtau);
    const double dn = incremental ? S.dn[k] + dot(vr, n) * tau : R - Lc;  // eqs 14, 16
    ContactForce3 f = advance_contact(S, static_cast<std::size_t>(k), params_, dn, n, vr, tau, dtau);
    Vec3 roll;
    if (rolling) {
      const Vec3 w_rel{wx[i] - wx[j], wy[i] - wy[j], wz[i] - wz[j]};
      roll = rolling_torque_3d(params_.mu_r, r[i] * r[j] / R, f.fn_spring, w_rel,
                               inv_i[i] + inv_i[j], dtau);
      f.loss.friction += std::sqrt(dot(roll, roll) * dot(w_rel, w_rel)) * dtau;
    }
    const double ratio = 1.0 - Lc / R;
    worst = ratio > max_ratio ? k : worst;
    max_ratio = std::max(max_ratio, ratio);
    sliding += f.sliding;
    ledger.add(static_cast<std::size_t>(i), 0.0, f.loss);
    on[count] = static_cast<std::int32_t>(k);
    cs.fx[k0 + count] = f.force.x;
    cs.fy[k0 + count] = f.force.y;
    cs.fz[k0 + count] = f.force.z;
    cs.ftx[k0 + count] = f.lever.x;
    cs.fty[k0 + count] = f.lever.y;
    cs.ft[k0 + count] = f.lever.z;
    cs.ratio[k0 + count] = ratio;
    cs.roll_x[k0 + count] = roll.x;
    cs.roll_y[k0 + count] = roll.y;
    cs.roll[k0 + count] = roll.z;
    if (j >= end) {
      pass.push_back(Push{f.force.x, f.force.y, f.lever.z, ratio, j, roll.z});
      pass_depth.push_back(PushDepth{f.force.z, f.lever.x, f.lever.y, roll.x, roll.y});
    }
    ++count;
  }
  acc.contacts = static_cast<int>(count);
  acc.sliding += sliding;
  acc.max_ratio = std::max(acc.max_ratio, max_ratio);
  acc.worst = worst;
}

bool DemSolver::particle_pass_depth(int t, std::size_t b, std::size_t e, double dtau,
                                    bool incremental, StepPartial& acc) {
  Particles& P = state_.particles;
  const double *x = P.x.data(), *y = P.y.data(), *z = P.z.data();
  const double *vx = P.vx.data(), *vy = P.vy.data(), *vz = P.vz.data();
  const double *wx = P.wx.data(), *wy = P.wy.data(), *wz = P.w.data();
  const double *r = P.radius.data(), *m = P.mass.data(), *inv_i = P.inv_inertia.data();
  double *fx = P.fx.data(), *fy = P.fy.data(), *fz = P.fz.data();
  double *tx = P.torque_x.data(), *ty = P.torque_y.data(), *tz = P.torque.data();
  double* ov = overlap_.data();
  const double g = gravity_;
  for (std::size_t blk = b / kParticleBlock; blk * kParticleBlock < e; ++blk) {
    const std::size_t i0 = std::max(b, blk * kParticleBlock);
    const std::size_t i1 = std::min(e, (blk + 1) * kParticleBlock);
    double gas = 0.0;
    for (std::size_t i = i0; i < i1; ++i) {
      fx[i] = P.ext_fx[i];
      fy[i] = P.ext_fy[i] - m[i] * g;
      fz[i] = P.ext_fz[i];
      tx[i] = ty[i] = tz[i] = 0.0;
      ov[i] = 0.0;
      gas += P.ext_fx[i] * vx[i] + P.ext_fy[i] * vy[i] + P.ext_fz[i] * vz[i];
    }
    block_ledger_[blk].gas_work += gas * dtau;
  }
  // A contact's force and torques on its second particle j.
  auto take = [&](std::int32_t j, const Vec3& f, const Vec3& lever, const Vec3& roll,
                  double ratio) {
    fx[j] -= f.x;
    fy[j] -= f.y;
    fz[j] -= f.z;
    tx[j] += r[j] * lever.x - roll.x;
    ty[j] += r[j] * lever.y - roll.y;
    tz[j] += r[j] * lever.z - roll.z;
    ov[j] = std::max(ov[j], ratio);
  };
  const auto lo = static_cast<std::int32_t>(b), hi = static_cast<std::int32_t>(e);
  for (int u = 0; u < t; ++u) {
    const auto& pass = passed_[static_cast<std::size_t>(u)];
    const auto& pass_depth = passed_depth_[static_cast<std::size_t>(u)];
    for (std::size_t q = 0; q < pass.size(); ++q) {
      const Push& c = pass[q];
      const PushDepth& d = pass_depth[q];
      if (c.j >= lo && c.j < hi)
        take(c.j, {c.fx, c.fy, d.fz}, {d.ftx, d.fty, c.ft}, {d.roll_x, d.roll_y, c.roll}, c.ratio);
    }
  }
  {
    const PairSlots& S = list_.slots();
    const std::int32_t* on = list_.active.data() + acc.k0;
    const ContactScratch& cs = list_.contact_scratch;
    for (int q = 0; q < acc.contacts; ++q) {
      const std::int64_t c = acc.k0 + q;
      const std::int32_t k = on[q];
      const std::int32_t i = S.i[k], j = S.j[k];
      const Vec3 f{cs.fx[c], cs.fy[c], cs.fz[c]};
      const Vec3 lever{cs.ftx[c], cs.fty[c], cs.ft[c]};
      const Vec3 roll{cs.roll_x[c], cs.roll_y[c], cs.roll[c]};
      fx[i] += f.x;
      fy[i] += f.y;
      fz[i] += f.z;
      tx[i] += r[i] * lever.x + roll.x;
      ty[i] += r[i] * lever.y + roll.y;
      tz[i] += r[i] * lever.z + roll.z;
      ov[i] = std::max(ov[i], cs.ratio[c]);
      if (j < hi) take(j, f, lever, roll, cs.ratio[c]);
    }
  }
  // Walls: the planar ones for the particles that can reach one before the next neighbour-list
  // build, then the front and back walls for every particle (a thick slab is a few diameters
  // deep: most of its particles are within reach of one of them).
  WallHistory& wh = state_.walls;
  const int nw = static_cast<int>(walls_.size());
  double max_wall_ratio = 0.0;
  BlockLedger wall_ledger(block_ledger_.data());
  int wall_contacts = 0, sliding = 0;
  auto wall_contact = [&](std::size_t i, int c) {
    const Wall& wall = walls_[static_cast<std::size_t>(c)];
    const std::size_t s = i * static_cast<std::size_t>(nw) + static_cast<std::size_t>(c);
    const double d = wall.nx * x[i] + wall.ny * y[i] + wall.nz * z[i] - wall.offset;
    if (!(d < r[i])) {  // apart: a contact that has just ended leaves no history
      if (wh.active[s]) {
        wh.active[s] = 0;
        wh.dn[s] = wh.ds[s] = wh.ds_y[s] = wh.ds_z[s] = 0.0;
      }
      return;
    }
    const bool fresh = !wh.active[s];
    wh.active[s] = 1;
    const Vec3 n{-wall.nx, -wall.ny, -wall.nz};  // from the particle into the wall
    const double overlap = r[i] - d;
    const Vec3 spin{wx[i], wy[i], wz[i]};
    const Vec3 vr = Vec3{vx[i], vy[i], vz[i]} + r[i] * cross(spin, n);
    const double vn = dot(vr, n);
    double tau = dtau;
    if (fresh && incremental) tau = std::min(time_since_touch_wall(overlap, vn), dtau);
    const double dn = incremental ? wh.dn[s] + vn * tau : overlap;
    ContactForce3 f = advance_contact(wh, s, params_, dn, n, vr, tau, dtau);
    Vec3 roll;
    if (params_.mu_r > 0.0) {
      roll = rolling_torque_3d(params_.mu_r, r[i], f.fn_spring, spin, inv_i[i], dtau);
      f.loss.friction += std::sqrt(dot(roll, roll) * dot(spin, spin)) * dtau;
    }
    wall_ledger.add(i, 0.0, f.loss);
    fx[i] += f.force.x;
    fy[i] += f.force.y;
    fz[i] += f.force.z;
    tx[i] += r[i] * f.lever.x + roll.x;
    ty[i] += r[i] * f.lever.y + roll.y;
    tz[i] += r[i] * f.lever.z + roll.z;
    sliding += f.sliding;
    max_wall_ratio = std::max(max_wall_ratio, overlap / r[i]);
    ov[i] = std::max(ov[i], 0.5 * overlap / r[i]);
    ++wall_contacts;
  };
  for (const std::int32_t ni : near_wall_[static_cast<std::size_t>(t)])
    for (const int c : planar_walls_) wall_contact(static_cast<std::size_t>(ni), c);
  for (std::size_t i = b; i < e; ++i)
    for (const int c : depth_walls_) wall_contact(i, c);
  return finish_particle_pass(b, e, wall_contacts, sliding, max_wall_ratio, acc);
}

}  // namespace fluidbed
