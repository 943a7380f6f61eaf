#pragma once
// The linear spring-dashpot contact with Coulomb friction (Xu & Yu 1997, eqs 3-7) and the
// paper's incremental displacements (eqs 13-17). Small stateless functions over a parameter
// struct: the solver picks the variant once per run, the hot loop has no virtual call.
//
// Sign convention: n points from particle i to its partner j (or into the wall); t = z x n.
// A displacement delta > 0 means compression (normal) or a shear of i's contact point along +t
// relative to j; the force on i is along -n for compression and against the shear.
#include <algorithm>
#include <cmath>
#include <numbers>

namespace fluidbed {

struct ContactParams {
  double kn = 50000.0;  // N/m, kappa_n
  double kt = 50000.0;  // N/m, kappa_t
  double eta_n = 0.15;  // kg/s
  double eta_t = 0.15;  // kg/s
  double mu = 0.3;      // gamma, Coulomb friction coefficient
  double mu_r = 0.0;    // rolling resistance (rolling_torque); 0: none
  // Hertz-Mindlin (contact.law = "hertz_mindlin", a thick slab): kn, kt, eta_n and eta_t above
  // are then each contact's own, from its overlap (hertz_params), and these are the material's.
  bool hertz = false;
  double hertz_kn = 0.0;       // Pa: (4/3) Y*; the normal spring is hertz_kn sqrt(R* dn)
  double hertz_kt = 0.0;       // Pa: 8 G*; the tangential spring is hertz_kt sqrt(R* dn)
  double hertz_damping = 0.0;  // 2 sqrt(5/6) |beta|, beta = ln e / sqrt(ln^2 e + pi^2)
};

// The Hertz-Mindlin contact of a pair (or a sphere and a wall) with effective radius r_eff
// (R_i R_j / (R_i + R_j); R_i at a wall) and mass m_eff (m_i m_j / (m_i + m_j); m_i at a wall) at
// the normal displacement dn, as the linear law's parameters (Tsuji et al., Powder Technol. 71
// (1992) 239; the form LIGGGHTS and Lethe use): with a = sqrt(r_eff dn),
//   kn = (4/3) Y* a, so that the normal force is (4/3) Y* sqrt(r_eff) dn^(3/2);
//   kt = 8 G* a;
//   eta_n = 2 sqrt(5/6) |beta| sqrt(S_n m_eff), S_n = 2 Y* a = 1.5 kn;
//   eta_t = 2 sqrt(5/6) |beta| sqrt(S_t m_eff), S_t = 8 G* a = kt.
// Friction and rolling resistance are the linear law's. Zero for dn <= 0.
inline ContactParams hertz_params(const ContactParams& p, double dn, double r_eff, double m_eff) {
  ContactParams c = p;
  const double a = std::sqrt(r_eff * std::max(dn, 0.0));
  c.kn = p.hertz_kn * a;
  c.kt = p.hertz_kt * a;
  c.eta_n = p.hertz_damping * std::sqrt(1.5 * c.kn * m_eff);
  c.eta_t = p.hertz_damping * std::sqrt(c.kt * m_eff);
  return c;
}

// The material's constants of hertz_params for spheres of Young's modulus E (Pa), Poisson's
// ratio nu and restitution e, against spheres and walls of the same material:
// Y* = E / (2 (1 - nu^2)), G* = G / (2 (2 - nu)) with G = E / (2 (1 + nu)).
inline void set_hertz(ContactParams& p, double E, double nu, double e) {
  const double y_eff = E / (2.0 * (1.0 - nu * nu));
  const double g_eff = E / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu));
  const double log_e = std::log(e);
  const double beta = log_e / std::sqrt(log_e * log_e + std::numbers::pi * std::numbers::pi);
  p.hertz = true;
  p.hertz_kn = 4.0 / 3.0 * y_eff;
  p.hertz_kt = 8.0 * g_eff;
  p.hertz_damping = 2.0 * std::sqrt(5.0 / 6.0) * std::fabs(beta);
}

// Force on i, as components along n and t, and whether the contact slides.
struct ContactForce {
  double fn = 0.0;  // N, along n (negative: pushes i away from j)
  double ft = 0.0;  // N, along t
  bool sliding = false;
};

// Eqs 3-7 for the normal displacement dn and the tangential (shear) displacement ds (m; ds is
// updated in place when the contact slides: the tangential
// spring is held at the Coulomb limit, so the contact sticks again as soon as the shear
// reverses). vn = v_r . n, vt = v_r . t + spin terms (eq 15's bracket). The normal spring acts
// in compression only; the dashpot acts over the whole contact, as in the damped oscillator.
inline ContactForce contact_force(const ContactParams& p, double dn, double& ds, double vn,
                                  double vt) {
  ContactForce f;
  const double fn_spring = -p.kn * std::max(dn, 0.0);   // eq 3
  f.fn = fn_spring - p.eta_n * vn;                        // eq 6
  const double ft_spring = -p.kt * ds;                     // eq 4
  const double limit = p.mu * std::fabs(fn_spring);       // eq 5
  if (std::fabs(ft_spring) > limit) {
    f.sliding = true;
    f.ft = ft_spring > 0.0 ? limit : -limit;  // friction alone while sliding
    if (p.kt > 0.0) ds = -f.ft / p.kt;
  } else {
    f.ft = ft_spring - p.eta_t * vt;  // eq 7
  }
  return f;
}

// What a contact dissipates over a step of h (J), from the quantities contact_force used: the
// dashpots' eta v^2 h (the tangential one only while the contact sticks), and while it slides the
// Coulomb force times the slip, the shear the spring gave up when it was held at its limit
// (ds_before: the displacement after this step's increment, before contact_force capped it).
struct ContactLoss {
  double dashpot = 0.0;   // J
  double friction = 0.0;  // J
};
inline ContactLoss contact_loss(const ContactParams& p, const ContactForce& f, double ds_before,
                                double ds_after, double vn, double vt, double h) {
  ContactLoss l;
  l.dashpot = p.eta_n * vn * vn * h;
  if (f.sliding) {
    l.friction = std::fabs(f.ft) * std::fabs(ds_before - ds_after);
  } else {
    l.dashpot += p.eta_t * vt * vt * h;
  }
  return l;
}

// Rolling resistance (an option; the paper's model has none), a constant torque against the
// relative rolling (Ai et al., Powder Technol. 206 (2011) 269, model A): on i,
// -mu_r R_r |F_n| sign(w_rel), with w_rel = w_i - w_j (w_i at a wall), R_r = R_i R_j / (R_i + R_j)
// (R_i at a wall) and F_n the spring's normal force (the one eq 5's Coulomb limit uses). Limited
// to the torque that stops the relative rolling within the step h, so that it never reverses it:
// |M| <= |w_rel| / (h k) with k = 1 / I_i + 1 / I_j (1 / I_i at a wall). It dissipates
// |M| |w_rel| h over the step.
inline double rolling_torque(double mu_r, double r_roll, double fn_spring, double w_rel,
                             double inv_inertia_sum, double h) {
  const double stop = std::fabs(w_rel) / (h * inv_inertia_sum);
  const double m = std::min(mu_r * r_roll * std::fabs(fn_spring), stop);
  return w_rel > 0.0 ? -m : (w_rel < 0.0 ? m : 0.0);
}

// The same law in three dimensions (a thick slab). n: unit normal from i to its partner (or into
// the wall); vr: the velocity of i's contact point relative to the partner's,
// v_i - v_j + (R_i w_i + R_j w_j) x n (at a wall v_i + R_i w_i x n); dn: the normal displacement,
// already advanced; s: the shear displacement vector (in/out), carried with the contact. Before
// this step's increment s is turned into the current contact plane - its normal part removed and
// the rest scaled back to its former length, so that a contact that rolls round its partner keeps
// its spring's stretch without creating normal force from it (as LIGGGHTS' history does) - then
// advanced by the tangential relative velocity over tau (eqs 15, 17 with the vector increment).
// Eqs 3-7 with |F_t| capped at mu |F_n spring| along the spring's direction. In the plane
// (n_z = 0, s along t = z x n) every quantity is that of contact_force.
struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 operator*(double k, const Vec3& a) { return {k * a.x, k * a.y, k * a.z}; }
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

struct ContactForce3 {
  Vec3 force;   // N, on i
  Vec3 lever;   // n x F_t (N): the torque on i is R_i lever, on a partner sphere R_j lever
  double fn_spring = 0.0;  // N, the normal spring (eq 3), for rolling resistance
  bool sliding = false;
  ContactLoss loss;
};
inline ContactForce3 contact_force_3d(const ContactParams& p, double dn, Vec3& s, const Vec3& n,
                                      const Vec3& vr, double tau, double h) {
  ContactForce3 f;
  const double vn = dot(vr, n);
  const Vec3 vt = vr - vn * n;
  const double s_len2 = dot(s, s);
  if (s_len2 > 0.0) {  // into the contact plane, at its former length
    const Vec3 in_plane = s - dot(s, n) * n;
    const double p_len2 = dot(in_plane, in_plane);
    s = p_len2 > 0.0 ? std::sqrt(s_len2 / p_len2) * in_plane : Vec3{};
  }
  s = s + tau * vt;
  const Vec3 s_before = s;
  f.fn_spring = -p.kn * std::max(dn, 0.0);  // eq 3
  const double fn = f.fn_spring - p.eta_n * vn;  // eq 6
  const Vec3 ft_spring = -p.kt * s;              // eq 4
  const double limit = p.mu * std::fabs(f.fn_spring);  // eq 5
  const double spring_len = std::sqrt(dot(ft_spring, ft_spring));
  Vec3 ft;
  if (spring_len > limit) {
    f.sliding = true;
    ft = (limit / spring_len) * ft_spring;  // friction alone while sliding
    if (p.kt > 0.0) s = (-1.0 / p.kt) * ft;
    const Vec3 slip = s_before - s;
    f.loss.friction = limit * std::sqrt(dot(slip, slip));
    f.loss.dashpot = p.eta_n * vn * vn * h;
  } else {
    ft = ft_spring - p.eta_t * vt;  // eq 7
    f.loss.dashpot = p.eta_n * vn * vn * h + p.eta_t * dot(vt, vt) * h;
  }
  f.force = fn * n + ft;
  f.lever = cross(n, ft);
  return f;
}

// Rolling resistance in three dimensions (rolling_torque along the relative spin): the torque on
// i against w_rel = w_i - w_j (the spin at a wall), limited as rolling_torque is.
inline Vec3 rolling_torque_3d(double mu_r, double r_roll, double fn_spring, const Vec3& w_rel,
                              double inv_inertia_sum, double h) {
  const double spin = std::sqrt(dot(w_rel, w_rel));
  if (spin <= 0.0) return {};
  const double m = rolling_torque(mu_r, r_roll, fn_spring, spin, inv_inertia_sum, h);  // <= 0
  return (m / spin) * w_rel;
}

// Eq 13: the time since two spheres first touched, found by moving j back from i along the
// relative velocity until their centres are R apart. p = x_j - x_i, w = v_j - v_i, L = |p| < R.
// Returns 0 when the spheres have no relative velocity (they were placed touching).
inline double time_since_touch(double px, double py, double wx, double wy, double R, double L,
                               double pz = 0.0, double wz = 0.0) {
  const double ww = wx * wx + wy * wy + wz * wz;
  if (ww <= 0.0) return 0.0;
  const double pw = px * wx + py * wy + pz * wz;
  const double disc = pw * pw + ww * (R * R - L * L);
  return (pw + std::sqrt(std::max(disc, 0.0))) / ww;
}

// The same for a plane: the particle's centre is `gap` short of touching distance (overlap > 0)
// and approaches the wall at speed vn.
inline double time_since_touch_wall(double overlap, double vn) {
  return vn > 0.0 ? overlap / vn : 0.0;
}

// Closed forms of the linear spring-dashpot for a head-on contact of effective mass m (kg: m/2
// for two equal spheres, m against a wall), spring k (N/m) and dashpot eta (kg/s).
//
// The contact's duration when undamped, half a period: t_c = pi sqrt(m / k) (s). The paper's
// step is t_c / 9 of a sphere on a wall (1.5e-5 s for 4 mm glass at 50,000 N/m).
inline double contact_duration(double k, double m) { return std::numbers::pi * std::sqrt(m / k); }

// The restitution coefficient: exp(-pi z / sqrt(1 - z^2)) with z = eta / (2 sqrt(k m)) the
// damping ratio (0 for an overdamped contact, z >= 1).
inline double restitution_from_damping(double k, double eta, double m) {
  const double z = eta / (2.0 * std::sqrt(k * m));
  if (z >= 1.0) return 0.0;
  return std::exp(-std::numbers::pi * z / std::sqrt(1.0 - z * z));
}

// The dashpot that keeps a contact's restitution when its spring changes from k0 to k: the
// restitution hangs on eta / sqrt(k m) alone, so eta scales with sqrt(k / k0).
inline double damping_for_stiffness(double eta0, double k0, double k) {
  return eta0 * std::sqrt(k / k0);
}

// Hertz's duration of an elastic head-on impact at speed v (m/s) of effective mass m_eff and radius
// r_eff, with hertz_kn = (4/3) Y*: 2.8683 (m_eff^2 / (r_eff Y*^2 v))^(1/5) (Johnson, Contact
// Mechanics, 1985, sec. 11.4): twice the time to the largest compression
// (15 m_eff v^2 / (16 Y* sqrt(r_eff)))^(2/5), 2 x 1.47164 of it over v (the integral of
// (1 - u^(5/2))^(-1/2) over [0, 1], Gamma(7/5) Gamma(1/2) / Gamma(9/10)).
inline double hertz_contact_duration(double hertz_kn, double r_eff, double m_eff, double v) {
  const double y_eff = 0.75 * hertz_kn;
  return 2.8683 * std::pow(m_eff * m_eff / (r_eff * y_eff * y_eff * v), 0.2);
}

}  // namespace fluidbed
