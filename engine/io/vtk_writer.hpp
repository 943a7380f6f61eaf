#pragma once
// ParaView-readable files of snapshots (VTK XML, no GL, no VTK library): the particles as
// PolyData (.vtp: points at the centres, z on the slab's mid-plane in a monolayer and the
// snapshot's z in a thick bed, with velocity, force, torque, spin, overlap, radius, initial
// height and id), the gas cells as ImageData (.vti: velocity, porosity, pressure per
// cell), and one .pvd collection per kind that ParaView opens as a time series. Arrays are
// inline base64 binary (a UInt32 byte count, then little-endian values), Float32 except ids.
#include <string>
#include <utility>
#include <vector>

#include "sim/snapshot.hpp"

namespace fluidbed {

void write_particles_vtp(const std::string& path, const Snapshot& s);
// Nothing is written for a snapshot without gas.
void write_gas_vti(const std::string& path, const Snapshot& s);
// The bubble analysis' fine void fraction (nothing for a snapshot without it).
void write_void_vti(const std::string& path, const Snapshot& s);

// A time series in a folder: particles_NNNNNN.vtp, gas_NNNNNN.vti and void_NNNNNN.vti (the fine
// void fraction) per snapshot, and particles.pvd, gas.pvd and void.pvd listing them with their
// times. The collections are rewritten after
// every snapshot (each complete or absent), so a run stopped half-way leaves a readable series.
// What a series has written: its snapshots' times and which collections it has (a resumed
// run's series continues from it).
struct VtkSeriesWritten {
  std::vector<double> times;  // s
  bool gas = false, void_fraction = false;
};

class VtkSeries {
 public:
  using Written = VtkSeriesWritten;
  // Creates the folder (InputError if it cannot); a series that continues `before` numbers its
  // next snapshot after those and lists them all in its collections.
  explicit VtkSeries(std::string dir, Written before = {});
  void write(const Snapshot& s);
  std::size_t size() const { return times_.size(); }
  Written written() const { return {times_, gas_, void_}; }

 private:
  void write_collection(const std::string& name, const std::string& ext) const;
  std::string dir_;
  std::vector<double> times_;
  bool gas_ = false, void_ = false;
};

}  // namespace fluidbed
