#pragma once
// Particles as a structure of arrays. The bed is pseudo-three-dimensional: centres move in the
// x-y plane on the slab's mid-plane, spin is about z only. A full 3D extension adds z, vz, az and
// the x, y spin components as further arrays beside these; nothing here assumes a pair count.
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
  // Constants.
  std::vector<double> radius;       // m
  std::vector<double> mass;         // kg
  std::vector<double> inv_mass;     // 1/kg
  std::vector<double> inv_inertia;  // 1/(kg m^2), sphere: I = 2/5 m R^2

  std::size_t size() const { return x.size(); }

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

  void resize(std::size_t n) {
    for (auto* v : {&x, &y, &vx, &vy, &w, &ax, &ay, &aw, &fx, &fy, &torque, &ext_fx, &ext_fy,
                    &radius, &mass, &inv_mass, &inv_inertia})
      v->assign(n, 0.0);
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
