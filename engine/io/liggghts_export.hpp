#pragma once
// A scene as a LIGGGHTS 3.8 case (`fluidbed export SCENE --to liggghts DIR`): an input deck and a
// LAMMPS-style data file with the scene's particles at their start, its walls and its contact
// law with the same numbers, so that a bed too big for one machine runs on LIGGGHTS with MPI and
// the benchmark compares the two codes on the same work. No GL, no LIGGGHTS needed to write it.
//
//   DIR/in.liggghts     the deck: plain LIGGGHTS commands, each block commented
//   DIR/particles.data  the start: one line per sphere (id type diameter density x y z), and the
//                       velocities when the start has any
// Running `cd DIR && liggghts -in in.liggghts` writes DIR/log.liggghts (thermo: kinetic
// energy every diagnostics.output_interval) and DIR/final.dump (id type radius x y z vx vy vz
// omegaz at time.end), which read_liggghts_dump reads back.
//
// What the deck keeps and what it cannot (said again in the deck's own comments):
// - The contact law is LIGGGHTS's `gran model hooke/stiffness tangential history` with
//   `absolute_damping on`: kn, kt (N/m), gamman_abs, gammat_abs (kg/s), coefficientFriction,
//   for particle pairs and the left, right, bottom (and top) walls alike. Two details differ from
//   fluidbed's contact_law.hpp: LIGGGHTS takes the normal overlap from the geometry (fluidbed's
//   default accumulates it, eqs 13-17), and it caps the tangential force at mu times the whole
//   normal force, dashpot included (fluidbed: mu times the spring force).
// - The gas is left out (LIGGGHTS is DEM only): a scene with [gas] is written without drag or
//   pressure force, and the deck says so.
// - Motion stays in the x-y plane because the z force is held at zero (fix setforce; the
//   spheres start on the slab's mid-plane at rest in z), not by front and back walls: those never
//   press on an in-plane sphere, give the same bed to the last digit, and cost time (the 0.8 s
//   packing of 2400 spheres on one core: 14 s with three walls, 27-28 s with the open slab's
//   five). LIGGGHTS's 2-d mode (dimension 2, fix enforce2d) is not used: it wants a periodic z
//   and takes the data file's density as mass per area.
// - LIGGGHTS integrates with velocity Verlet (fix nve/sphere). Scenes with time.integrator
//   "velocity_verlet" or "newmark" (second order both) are written; "symplectic_euler" (first
//   order) is refused.
// - placement "lattice" and "single" are written as they start; "state" writes the saved
//   positions, velocities and spins but not the contact history (LIGGGHTS's data file has no
//   place for it: tangential springs restart from zero, normal overlaps come from the geometry);
//   "packed" writes the lattice start and runs the packing (packing_time, gas left out) as a
//   first stage of the deck, with the packing scene's contact law when particles.packing_scene
//   names one. A frozen bed (particles.frozen) has nothing to move without the gas: refused.
#include <cstdint>
#include <string>
#include <vector>

#include "dem/particles.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

struct LiggghtsExportOptions {
  // Front and back walls as wall/gran z planes, z left free: the slab as six walls. Slower than
  // holding z (the default); kept for the timing comparison.
  bool front_back_walls = false;
  // Every so many seconds of the scene's run, a snapshot of every sphere in DIR/frames.dump
  // (id type radius x y z vx vy vz omegaz, full precision): the energy comparison reads it.
  // 0: none.
  double frames_every = 0.0;  // s
};

struct LiggghtsCase {
  std::string deck;                // path of in.liggghts
  std::string data;                // path of particles.data
  std::vector<std::string> notes;  // what the deck leaves out or changes, one line each
};

// Writes DIR/in.liggghts and DIR/particles.data (creating DIR). Throws InputError for a scene
// the deck cannot express (see above) or a folder that cannot be written.
LiggghtsCase write_liggghts_case(const Settings& s, const std::string& dir,
                                 const LiggghtsExportOptions& options = {});

// The snapshots of a LIGGGHTS `custom` dump with columns id, radius, x, y (others ignored, any
// order; vx, vy and omegaz read when present), each in id order. Masses from `density`.
// Throws InputError when the file cannot be read or lacks a column.
struct LiggghtsFrame {
  std::int64_t step = 0;
  Particles particles;
};
std::vector<LiggghtsFrame> read_liggghts_frames(const std::string& path, double density);
// The last snapshot of such a dump.
Particles read_liggghts_dump(const std::string& path, double density);

}  // namespace fluidbed
