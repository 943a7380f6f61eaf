#pragma once
// Synthetic snapshots and pixel checks for the render tests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "render/colour_map.hpp"
#include "render/image.hpp"
#include "sim/snapshot.hpp"

namespace fluidbed::testing {

// An empty box of width x height (m), at t = 1.25 s, with a jet slot and no gas cells.
inline Snapshot empty_box(double width = 0.1, double height = 0.1) {
  Snapshot s;
  s.time = 1.25;
  s.step = 1000;
  s.dt = 1e-5;
  s.width = width;
  s.height = height;
  s.thickness = 0.004;
  s.inlet_kind = InletKind::Jet;
  s.jet_width = 0.01;
  s.superficial_velocity = 2.8;
  s.jet_velocity = 42.0;
  return s;
}

struct ParticleState {
  double x, y, r;
  double vx = 0, vy = 0, fx = 0, fy = 0, torque = 0, overlap = 0, initial_y = 0;
};

inline void add_particle(Snapshot& s, const ParticleState& p) {
  s.x.push_back(p.x);
  s.y.push_back(p.y);
  s.radius.push_back(p.r);
  s.vx.push_back(p.vx);
  s.vy.push_back(p.vy);
  s.spin.push_back(0.0);
  s.fx.push_back(p.fx);
  s.fy.push_back(p.fy);
  s.torque.push_back(p.torque);
  s.overlap.push_back(p.overlap);
  s.initial_y.push_back(p.initial_y);
}

// Gas cells nx x ny at rest, porosity 1, pressure 0.
inline void add_gas(Snapshot& s, int nx, int ny) {
  s.nx = nx;
  s.ny = ny;
  const auto n = static_cast<std::size_t>(nx * ny);
  s.gas_ux.assign(n, 0.0);
  s.gas_uy.assign(n, 0.0);
  s.porosity.assign(n, 1.0);
  s.pressure.assign(n, 0.0);
}

struct Rgb8 {
  int r, g, b;
};

// The pixel holding (x, y) (px, y down); outside the image: a test failure and (-1, -1, -1).
inline Rgb8 at(const render::Image& img, float x, float y) {
  const auto ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  if (ix < 0 || iy < 0 || ix >= img.width || iy >= img.height) {
    ADD_FAILURE() << "pixel (" << x << ", " << y << ") is outside the " << img.width << "x"
                  << img.height << " image";
    return {-1, -1, -1};
  }
  const auto* p = img.pixel(ix, iy);
  return {p[0], p[1], p[2]};
}

inline Rgb8 to8(render::Rgb c) {
  return {static_cast<int>(std::lround(c.r * 255.0f)), static_cast<int>(std::lround(c.g * 255.0f)),
          static_cast<int>(std::lround(c.b * 255.0f))};
}

inline ::testing::AssertionResult near(Rgb8 got, Rgb8 want, int tolerance) {
  if (std::abs(got.r - want.r) <= tolerance && std::abs(got.g - want.g) <= tolerance &&
      std::abs(got.b - want.b) <= tolerance)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "pixel (" << got.r << ", " << got.g << ", " << got.b << ") is not within " << tolerance
         << " of (" << want.r << ", " << want.g << ", " << want.b << ")";
}

// Nearly white: the inside of the bed with nothing drawn on it.
inline bool is_background(Rgb8 c) { return c.r > 245 && c.g > 245 && c.b > 245; }
// Clearly drawn on: far from white.
inline bool is_ink(Rgb8 c) { return c.r + c.g + c.b < 3 * 160; }

}  // namespace fluidbed::testing
