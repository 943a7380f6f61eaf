#pragma once
// An immutable copy of what a picture, a file or a panel needs from the simulation at one
// instant. The engine thread fills one after a step and publishes it; readers (renderer, VTK
// writer, viewer) never touch the live state.
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/binary_io.hpp"
#include "scene/options.hpp"

namespace fluidbed {

class Simulation;

struct Snapshot {
  double time = 0.0;       // s
  std::int64_t step = 0;
  double dt = 0.0;         // s
  // Domain and inlet.
  double width = 0.0, height = 0.0, thickness = 0.0;  // m
  bool top_wall = false;
  InletKind inlet_kind = InletKind::None;  // the inlet (None without gas)
  double jet_width = 0.0;               // m, each slot
  int jets = 1;                         // slots centred at (k + 1/2) width / jets
  double superficial_velocity = 0.0;    // m/s
  double jet_velocity = 0.0;            // m/s
  double dp = 0.0;                      // Pa, bottom to top on the symmetry line
  double max_overlap_ratio = 0.0;
  double kinetic_energy = 0.0;          // J
  int contacts = 0;
  // Particles (index = particle id).
  std::vector<double> x, y, radius;     // m
  std::vector<double> z;                // m, across the slab from the front wall (empty in a monolayer)
  std::vector<double> vx, vy, spin;     // m/s, rad/s
  std::vector<double> fx, fy, torque;   // N, N m: total force (contacts, gravity, gas) and torque
  // A thick bed's other components (empty in a monolayer): velocity and force across the slab,
  // spin and torque about x and y.
  std::vector<double> vz, fz;                  // m/s, N
  std::vector<double> spin_x, spin_y;          // rad/s
  std::vector<double> torque_x, torque_y;      // N m
  std::vector<double> overlap;          // largest overlap ratio of each particle's contacts
  std::vector<double> initial_y;        // m, height at the start of the run (mixing colours)
  // Gas (empty without gas): nx * ny cells, c = j * nx + i.
  int nx = 0, ny = 0;
  // m: the grid's bottom, below the floor (y = 0) by a plenum's height; the cells are
  // width / nx wide and (height - gas_bottom) / ny high.
  double gas_bottom = 0.0;
  double gas_dy() const { return ny > 0 ? (height - gas_bottom) / ny : 0.0; }  // m, a cell's height
  std::vector<double> gas_ux, gas_uy;   // m/s, interstitial velocity at cell centres
  std::vector<double> porosity;         // -
  std::vector<double> pressure;         // Pa
  // The bubble analysis' fine grid, when the snapshot's taker computed it (frames with
  // --bubble-outlines, VTK files): void fraction per cell (c = j * void_nx + i, cells of
  // void_dx x void_dy), and the outlines of the bubbles and jet cavities found in it, as
  // segments x0 y0 x1 y1 (m), four values each.
  int void_nx = 0, void_ny = 0;
  double void_dx = 0.0, void_dy = 0.0;  // m
  std::vector<float> void_fraction;
  std::vector<float> bubble_edges;

  std::size_t particles() const { return x.size(); }
  // Magnitudes of particle i's velocity (m/s), force (N) and torque (N m): in the plane for a
  // monolayer, in three dimensions for a thick bed.
  double speed(std::size_t i) const { return magnitude(vx[i], vy[i], vz, i); }
  double force(std::size_t i) const { return magnitude(fx[i], fy[i], fz, i); }
  double torque_magnitude(std::size_t i) const {
    return i < torque_x.size() ? magnitude(torque_x[i], torque_y[i], torque, i)
                               : std::abs(torque[i]);
  }
  bool has_gas() const { return nx > 0; }

 private:
  static double magnitude(double a, double b, const std::vector<double>& c, std::size_t i) {
    return i < c.size() ? std::sqrt(a * a + b * b + c[i] * c[i]) : std::hypot(a, b);
  }
};

// Copies the simulation's state into `out` (reusing its buffers).
void take_snapshot(const Simulation& sim, Snapshot& out);

// A snapshot as bytes and back, every field (a run's checkpoint keeps its montage's snapshots).
void save_snapshot(std::ostream& out, const Snapshot& s);
void load_snapshot(BinarySource& in, Snapshot& s);

// The hand-off between the engine thread and its readers: the writer publishes a whole snapshot,
// a reader takes the newest one. The lock is held only to swap a pointer, never while a snapshot
// is filled or drawn, so the engine never waits for the screen.
class SnapshotChannel {
 public:
  // Returns a buffer the writer may fill (not visible to readers until published).
  std::shared_ptr<Snapshot> acquire();
  void publish(std::shared_ptr<Snapshot> s);
  // The newest published snapshot (nullptr before the first), and its sequence number.
  std::shared_ptr<const Snapshot> latest(std::uint64_t* sequence = nullptr) const;
  std::uint64_t sequence() const { return sequence_.load(std::memory_order_acquire); }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<Snapshot> latest_;
  std::shared_ptr<Snapshot> spare_;
  std::atomic<std::uint64_t> sequence_{0};
};

}  // namespace fluidbed
