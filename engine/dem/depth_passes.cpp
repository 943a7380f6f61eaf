// The particle step's two force passes for a thick slab, where particles move in three
// dimensions: the same structure as the monolayer's (DemSolver::pair_pass, particle_pass, with
// the same order of summation, so that results are the same bits for any thread count), with the
// contact law of contact_force_3d and the front and back walls as real contacts. The pairs and
// the walls run the law several contacts at a time (dem/pair_kernel.hpp: depth_contacts,
// wall_contacts_depth).
#include <algorithm>
#include <array>
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

namespace {

// What particle_pass_depth's listing of sphere-wall contacts reads and writes, as plain pointers:
// the history's flags are bytes, and through a member or a reference every other pointer would
// be loaded again after each of their stores.
struct WallLister {
  const double *x, *y, *z, *r;
  const double *nx, *ny, *nz, *offset;  // the walls'
  std::uint8_t* active;                 // the walls' history, [i * walls + c]
  double *dn, *ds, *ds_y, *ds_z;
  std::int32_t *on, *particle;  // the chunk: the history's slot (~slot when fresh), the sphere
  std::size_t walls;
};

// The contact of sphere i with a wall at the history's slot s, branch-free: written at `listed`,
// which moves on when they touch (the slot as ~slot the first time); apart, a contact that has
// just ended leaves no history. Returns the new count of listed contacts.
inline std::int64_t list_entry(const WallLister& L, std::size_t s, std::size_t i, int touching,
                               int was, std::int64_t listed) {
  if (was & (touching ^ 1)) L.dn[s] = L.ds[s] = L.ds_y[s] = L.ds_z[s] = 0.0;
  L.active[s] = static_cast<std::uint8_t>(touching);
  L.on[listed] = static_cast<std::int32_t>(s) ^ -(touching & (was ^ 1));
  L.particle[listed] = static_cast<std::int32_t>(i);
  return listed + touching;
}

// Sphere i against walls cs[0, count), in that order.
inline std::int64_t list_wall(const WallLister& L, std::size_t i, const int* cs, std::int64_t count,
                              std::int64_t listed) {
  for (std::int64_t k = 0; k < count; ++k) {
    const int c = cs[k];
    const std::size_t s = i * L.walls + static_cast<std::size_t>(c);
    const double d = L.nx[c] * L.x[i] + L.ny[c] * L.y[i] + L.nz[c] * L.z[i] - L.offset[c];
    listed = list_entry(L, s, i, d < L.r[i], L.active[s], listed);
  }
  return listed;
}

}  // namespace

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
  // Sphere i against each wall of `which`, in that order, then sphere i + 1; a chunk is passed
  // to the kernel when it may not hold another sphere's contacts (where a chunk ends changes no
  // result: each contact's law is on its own, and they are added in the listed order).
  const WallLister lister{x,
                          y,
                          z,
                          r,
                          wall_nx_.data(),
                          wall_ny_.data(),
                          wall_nz_.data(),
                          wall_offset_.data(),
                          wh.active.data(),
                          wh.dn.data(),
                          wh.ds.data(),
                          wh.ds_y.data(),
                          wh.ds_z.data(),
                          chunk.on.data(),
                          chunk.particle.data(),
                          static_cast<std::size_t>(nw)};
  auto list_walls = [&](auto next, std::size_t count, const std::vector<int>& which) {
    const WallLister L = lister;  // a local copy: no store of the listing can reach it
    const int* ws = which.data();
    const auto per = static_cast<std::int64_t>(which.size());
    for (std::size_t q = 0; q < count;) {
      std::int64_t n = listed;
      for (; q < count && n + per <= kWallChunk; ++q) n = list_wall(L, next(q), ws, per, n);
      listed = n;
      if (n + per > kWallChunk) add_chunk();
    }
  };
  const std::vector<std::int32_t>& near = near_wall_[static_cast<std::size_t>(t)];
  list_walls([ids = near.data()](std::size_t q) { return static_cast<std::size_t>(ids[q]); },
             near.size(), planar_walls_);
  // The front and back walls for every sphere, kWallScan spheres at a time: first, for each
  // wall, whether each sphere touches it (a loop of arithmetic alone), then the contacts that
  // touch or touched at the last step picked out in sphere order (branch-free), then those listed
  // as list_wall lists them (the others would change nothing). Measured on the slab bench: the
  // contacts 1.3 to 1.4 x faster than with list_wall over every sphere, whose stores to the
  // history's byte flags kept the loop from running ahead.
  const WallLister L = lister;
  const std::size_t nd = depth_walls_.size();  // 2 (dem/walls.hpp), at most kDepthWalls
  std::array<std::array<std::uint8_t, kWallScan>, kDepthWalls> flag{};
  std::array<std::uint16_t, kWallScan * kDepthWalls> pick{};
  std::array<std::size_t, kDepthWalls> depth_c{};
  for (std::size_t w = 0; w < nd; ++w) depth_c[w] = static_cast<std::size_t>(depth_walls_[w]);
  for (std::size_t i0 = b; i0 < e; i0 += kWallScan) {
    const std::size_t n = std::min(kWallScan, e - i0);
    for (std::size_t w = 0; w < nd; ++w) {
      const std::size_t c = depth_c[w];
      const double cx = L.nx[c], cy = L.ny[c], cz = L.nz[c], off = L.offset[c];
      std::uint8_t* f = flag[w].data();
      const double *xs = x + i0, *ys = y + i0, *zs = z + i0, *rs = r + i0;
#pragma omp simd
      for (std::size_t k = 0; k < n; ++k) {
        const double d = cx * xs[k] + cy * ys[k] + cz * zs[k] - off;
        f[k] = d < rs[k] ? 1 : 0;
      }
    }
    std::size_t picked = 0;
    for (std::size_t k = 0; k < n; ++k)
      for (std::size_t w = 0; w < nd; ++w) {
        const std::uint8_t was = L.active[(i0 + k) * L.walls + depth_c[w]];
        flag[w][k] = static_cast<std::uint8_t>(flag[w][k] | (was << 1));
        pick[picked] = static_cast<std::uint16_t>(k * kDepthWalls + w);
        picked += flag[w][k] != 0 ? 1 : 0;
      }
    for (std::size_t q = 0; q < picked; ++q) {
      const std::size_t k = pick[q] / kDepthWalls, w = pick[q] % kDepthWalls;
      const std::size_t i = i0 + k;
      const std::size_t s = i * L.walls + depth_c[w];
      listed = list_entry(L, s, i, flag[w][k] & 1, flag[w][k] >> 1, listed);
      if (listed == kWallChunk) add_chunk();
    }
  }
  add_chunk();
  return finish_particle_pass(b, e, wall_contacts, sliding, max_wall_ratio, acc);
}

}  // namespace fluidbed
