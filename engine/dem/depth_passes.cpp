// The particle step's two force passes for a thick slab, where particles move in three
// dimensions: the same structure as the monolayer's (DemSolver::pair_pass, particle_pass, with
// the same order of summation, so that results are the same bits for any thread count), with the
// contact law of contact_force_3d and the front and back walls as real contacts. The pairs and
// the walls run the law several contacts at a time (dem/pair_kernel.hpp: depth_contacts,
// wall_contacts_depth).
#include <algorithm>
#include <cmath>

#include "core/threads.hpp"
#include "dem/block_ledger.hpp"
#include "dem/dem_solver.hpp"
#include "dem/pair_kernel.hpp"

namespace fluidbed {

// As pair_pass: which pairs touch, the touching slots listed, the law over those
// (dem/pair_kernel.hpp: depth_contacts, several pairs at a time) into the compact scratch, then in
// slot order their history back to the slots, the diagnostics, the ledger and the contacts passed
// to later threads.
void DemSolver::pair_pass_depth(int t, std::size_t e, double dtau, bool incremental,
                                StepPartial& acc) {
  const Particles& P = state_.particles;
  const DepthKernelParticles pk{P.x.data(),  P.y.data(),      P.z.data(),           P.vx.data(),
                                P.vy.data(), P.vz.data(),     P.wx.data(),          P.wy.data(),
                                P.w.data(),  P.radius.data(), P.inv_inertia.data(), P.mass.data()};
  NeighbourList& L = list_;
  PairSlots& S = L.slots();
  const std::int64_t k0 = acc.k0, k1 = S.first_begin[e];
  const std::int32_t *li = S.i.data(), *lj = S.j.data();
  double *ldn = S.dn.data(), *lds = S.ds.data(), *lds_y = S.ds_y.data(), *lds_z = S.ds_z.data();
  std::uint8_t* code = L.code.data() + k0;
  classify_pairs_depth(pk, li, lj, k0, k1, code);
  std::int32_t* on = L.active.data() + k0;
  double max_ratio = 0.0;
  std::int64_t worst = -1;
  const std::int64_t count =
      list_touching(code, S.touching.data(), k0, k1, on, max_ratio, worst,
                    [&](std::int64_t k) { ldn[k] = lds[k] = lds_y[k] = lds_z[k] = 0.0; });
  ContactScratch& cs = L.contact_scratch;
  const DepthContactOut out{cs.dn.data() + k0,       cs.ds.data() + k0,     cs.ds_y.data() + k0,
                            cs.ds_z.data() + k0,     cs.fx.data() + k0,     cs.fy.data() + k0,
                            cs.fz.data() + k0,       cs.ftx.data() + k0,    cs.fty.data() + k0,
                            cs.ft.data() + k0,       cs.roll_x.data() + k0, cs.roll_y.data() + k0,
                            cs.roll.data() + k0,     cs.ratio.data() + k0,  cs.dashpot.data() + k0,
                            cs.friction.data() + k0, cs.sliding.data() + k0};
  depth_contacts({pk, li, lj, ldn, lds, on, count, params_, incremental, dtau, lds_y, lds_z}, out);
  int sliding = 0;
  std::vector<Push>& pass = passed_[static_cast<std::size_t>(t)];
  std::vector<PushDepth>& pass_depth = passed_depth_[static_cast<std::size_t>(t)];
  pass.clear();
  pass_depth.clear();
  const auto end = static_cast<std::int32_t>(e);
  BlockLedger ledger(block_ledger_.data());  // by the pairs' first particles: they come in i order
  for (std::int64_t q = 0; q < count; ++q) {
    const std::int32_t k = listed_slot(on[q]);
    ldn[k] = out.dn[q];
    lds[k] = out.ds[q];
    lds_y[k] = out.ds_y[q];
    lds_z[k] = out.ds_z[q];
    const double ratio = out.ratio[q];
    worst = ratio > max_ratio ? k : worst;
    max_ratio = std::max(max_ratio, ratio);
    sliding += out.sliding[q];
    ledger.add(static_cast<std::size_t>(li[k]), 0.0, ContactLoss{out.dashpot[q], out.friction[q]});
    if (lj[k] >= end) {
      pass.push_back(Push{out.fx[q], out.fy[q], out.lever_z[q], ratio, lj[k], out.roll_z[q]});
      pass_depth.push_back(
          PushDepth{out.fz[q], out.lever_x[q], out.lever_y[q], out.roll_x[q], out.roll_y[q]});
    }
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
      const std::int32_t k = listed_slot(on[q]);
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
  // deep: most of its particles are within reach of one of them). The touching ones are listed
  // in that order a chunk at a time, their law computed by the kernel (dem/pair_kernel.hpp:
  // wall_contacts_depth) and added in the same order.
  WallHistory& wh = state_.walls;
  const auto nw = static_cast<std::int32_t>(walls_.size());
  WallChunk& chunk = wall_chunks_[static_cast<std::size_t>(t)];
  ContactScratch& cs = chunk.out;
  const DepthContactOut out{
      cs.dn.data(),       cs.ds.data(),     cs.ds_y.data(), cs.ds_z.data(),  cs.fx.data(),
      cs.fy.data(),       cs.fz.data(),     cs.ftx.data(),  cs.fty.data(),   cs.ft.data(),
      cs.roll_x.data(),   cs.roll_y.data(), cs.roll.data(), cs.ratio.data(), cs.dashpot.data(),
      cs.friction.data(), cs.sliding.data()};
  WallContactIn in{{x, y, z, vx, vy, vz, wx, wy, wz, r, inv_i, m},
                   chunk.on.data(),
                   chunk.particle.data(),
                   0,
                   nw,
                   wall_nx_.data(),
                   wall_ny_.data(),
                   wall_nz_.data(),
                   wall_offset_.data(),
                   wh.dn.data(),
                   wh.ds.data(),
                   wh.ds_y.data(),
                   wh.ds_z.data(),
                   wall_params_,
                   incremental,
                   dtau};
  double max_wall_ratio = 0.0;
  BlockLedger wall_ledger(block_ledger_.data());
  int wall_contacts = 0, sliding = 0;
  std::int64_t listed = 0;
  auto add_chunk = [&] {
    in.count = listed;
    wall_contacts_depth(in, out);
    for (std::int64_t q = 0; q < listed; ++q) {
      const auto i = static_cast<std::size_t>(chunk.particle[q]);
      const auto s = static_cast<std::size_t>(listed_slot(chunk.on[q]));
      wh.dn[s] = out.dn[q];
      wh.ds[s] = out.ds[q];
      wh.ds_y[s] = out.ds_y[q];
      wh.ds_z[s] = out.ds_z[q];
      wall_ledger.add(i, 0.0, ContactLoss{out.dashpot[q], out.friction[q]});
      fx[i] += out.fx[q];
      fy[i] += out.fy[q];
      fz[i] += out.fz[q];
      tx[i] += r[i] * out.lever_x[q] + out.roll_x[q];
      ty[i] += r[i] * out.lever_y[q] + out.roll_y[q];
      tz[i] += r[i] * out.lever_z[q] + out.roll_z[q];
      sliding += out.sliding[q];
      max_wall_ratio = std::max(max_wall_ratio, out.ratio[q]);
      ov[i] = std::max(ov[i], 0.5 * out.ratio[q]);
    }
    wall_contacts += static_cast<int>(listed);
    listed = 0;
  };
  // Sphere i against wall c: listed when they touch (~s the first time); apart, a contact that
  // has just ended leaves no history.
  auto list_wall = [&](std::size_t i, int c) {
    const Wall& wall = walls_[static_cast<std::size_t>(c)];
    const std::size_t s = i * static_cast<std::size_t>(nw) + static_cast<std::size_t>(c);
    const double d = wall.nx * x[i] + wall.ny * y[i] + wall.nz * z[i] - wall.offset;
    const int touching = d < r[i], was = wh.active[s];
    if (was & (touching ^ 1)) wh.dn[s] = wh.ds[s] = wh.ds_y[s] = wh.ds_z[s] = 0.0;
    wh.active[s] = static_cast<std::uint8_t>(touching);
    chunk.on[static_cast<std::size_t>(listed)] =
        static_cast<std::int32_t>(s) ^ -(touching & (was ^ 1));
    chunk.particle[static_cast<std::size_t>(listed)] = static_cast<std::int32_t>(i);
    listed += touching;
    if (listed == kWallChunk) add_chunk();
  };
  for (const std::int32_t ni : near_wall_[static_cast<std::size_t>(t)])
    for (const int c : planar_walls_) list_wall(static_cast<std::size_t>(ni), c);
  for (std::size_t i = b; i < e; ++i)
    for (const int c : depth_walls_) list_wall(i, c);
  add_chunk();
  return finish_particle_pass(b, e, wall_contacts, sliding, max_wall_ratio, acc);
}

}  // namespace fluidbed
