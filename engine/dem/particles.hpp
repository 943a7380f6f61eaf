#pragma once
// Particles as a structure of arrays. In a monolayer (a slab one diameter thick, the paper's bed)
// centres move in the x-y plane on the slab's mid-plane and spin is about z only: the depth arrays
// below are empty. In a thicker slab (Particles::has_depth) they hold the third dimension: z, its
// velocity, acceleration and forces, and the x and y components of spin, its rate and the torque,
// beside the z components (w, aw, torque) that both modes share.
#include <cstddef>
#include <numbers>
#include <cstdint>
#include <vector>

namespace fluidbed {

struct Particles {
  // Integrated every step (hot).
  std::vector<double> x, y;     // m, centre
  std::vector<double> vx, vy;   // m/s
  std::vector<double> w;        // rad/s, spin about z
  std::vector<double> ax, ay;   // m/s^2, acceleration at the last force evaluation
  std::vector<double> aw;       // rad/s^2
  // Results of the last force evaluation, for diagnostics and pictures.
  std::vector<double> fx, fy;   // N, total force (contacts, gravity, gas)
  std::vector<double> torque;   // N m, about z
  // Forces from outside the particle model (the gas), held constant over a step.
  std::vector<double> ext_fx, ext_fy;  // N
  // The third dimension (empty in a monolayer): z across the slab (0 at the front wall).
  std::vector<double> z, vz, az, fz, ext_fz;  // m, m/s, m/s^2, N, N
  std::vector<double> wx, wy;                 // rad/s, spin about x and y
  std::vector<double> awx, awy;               // rad/s^2
  std::vector<double> torque_x, torque_y;     // N m
  // Constants.
  std::vector<double> radius;       // m
  std::vector<double> mass;         // kg
  std::vector<double> inv_mass;     // 1/kg
  std::vector<double> inv_inertia;  // 1/(kg m^2), sphere: I = 2/5 m R^2

  std::size_t size() const { return x.size(); }
  bool has_depth() const { return !z.empty(); }

  // The depth arrays of a thick slab, sized to the particles and zero (z at `mid`, m).
  void add_depth(double mid) {
    for (auto* v : depth_arrays()) v->assign(size(), 0.0);
    z.assign(size(), mid);
  }
  std::vector<std::vector<double>*> depth_arrays() {
    return {&z, &vz, &az, &fz, &ext_fz, &wx, &wy, &awx, &awy, &torque_x, &torque_y};
  }
  std::vector<const std::vector<double>*> depth_arrays() const {
    return {&z, &vz, &az, &fz, &ext_fz, &wx, &wy, &awx, &awy, &torque_x, &torque_y};
  }

  // Raw pointers to the arrays, taken once before a hot loop (so that the compiler need not
  // reload them from the vectors after every store).
  template <class T>
  struct Arrays {
    T *x, *y, *vx, *vy, *w, *ax, *ay, *aw, *fx, *fy, *torque, *ext_fx, *ext_fy;
    const double *radius, *mass, *inv_mass, *inv_inertia;
  };
  Arrays<double> arrays() {
    return {x.data(), y.data(), vx.data(), vy.data(), w.data(), ax.data(), ay.data(),
            aw.data(), fx.data(), fy.data(), torque.data(), ext_fx.data(), ext_fy.data(),
            radius.data(), mass.data(), inv_mass.data(), inv_inertia.data()};
  }
  Arrays<const double> arrays() const {
    return {x.data(), y.data(), vx.data(), vy.data(), w.data(), ax.data(), ay.data(),
            aw.data(), fx.data(), fy.data(), torque.data(), ext_fx.data(), ext_fy.data(),
            radius.data(), mass.data(), inv_mass.data(), inv_inertia.data()};
  }

  // Bytes of a particle's arrays (17 doubles; a thick slab's 11 more): what a bed must stream from
  // memory when it leaves the cache.
  static constexpr std::size_t bytes_per_particle(bool depth) { return 8 * (depth ? 28 : 17); }

  // Every array held (the depth arrays in a thick slab only), for what is done to all alike.
  std::vector<std::vector<double>*> all_arrays() {
    std::vector<std::vector<double>*> a = {&x,      &y,      &vx,     &vy,     &w,    &ax,
                                           &ay,     &aw,     &fx,     &fy,     &torque, &ext_fx,
                                           &ext_fy, &radius, &mass,   &inv_mass, &inv_inertia};
    if (has_depth())
      for (auto* v : depth_arrays()) a.push_back(v);
    return a;
  }

  void resize(std::size_t n) {
    for (auto* v : all_arrays()) v->assign(n, 0.0);
  }

  // Sets radius and the derived mass properties of particle i from its diameter and density.
  void set_sphere(std::size_t i, double diameter, double density) {
    constexpr double kPi = std::numbers::pi;
    radius[i] = 0.5 * diameter;
    mass[i] = density * kPi * diameter * diameter * diameter / 6.0;
    inv_mass[i] = 1.0 / mass[i];
    inv_inertia[i] = 1.0 / (0.4 * mass[i] * radius[i] * radius[i]);
  }
};

}  // namespace fluidbed
