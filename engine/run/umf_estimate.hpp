#pragma once
// A scene's own minimum fluidization velocity, measured from its model (the viewer's presets,
// slider scale and lessons): as the sweep finds it (the paper's Fig. 6, point E), from a
// decreasing branch of the scene's own velocity sweep (run/velocity_sweep.hpp,
// decreasing_only): its packed bed at the top of decreasing_branch_velocities(scene), then down
// through them, 2 s at each averaged from 1 s, U_mf where the defluidization line meets the
// plateau. When that branch gives no U_mf (a bed too small for a plateau), the fixed-bed force
// balance stands in, and says so: the velocity at which the fluid force the model puts on its
// packed bed, held fixed with a uniform inflow, equals the bed's weight (the test
// CoupledBed.MinimumFluidizationFromTheModel; it is 13 % above the sweep's on the paper's bed, a
// packed bed being denser than a defluidized one). The answer is cached beside the packed bed
// (run/packed_bed.hpp), by the hash of the settings that decide it, so a scene is measured once;
// a folder of shipped answers (the same files) is read after the cache.
#include <functional>
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed {

struct UmfEstimate {
  double umf = 0.0;     // m/s
  double wen_yu = 0.0;  // m/s, Wen and Yu's correlation for the same particles and gas
  int evaluations = 0;  // runs made (0 when read from a cache)
  bool from_cache = false;
  bool from_sweep = false;        // false: the fixed-bed force balance stood in
  std::string cache_file;         // where it is (or was read from)
  std::vector<double> u, dp;      // the decreasing branch (m/s, Pa), when from_sweep
  // Scaled from another scene's (umf_for_particles): that scene's U_mf (m/s; 0: not scaled) and
  // the ratio of the two force balances it was multiplied by.
  double scaled_from = 0.0, scale = 1.0;
  // How it was measured: one line for a panel, and a few words for a class.
  std::string method() const;
  std::string method_short() const;
};

// The fluid force on the frozen packed bed over its weight at superficial velocity u (m/s), after
// 0.03 s of uniform inflow. `fixed`: from fixed_bed_settings.
double fixed_bed_lift(const Settings& fixed, double u);
// The scene's packed bed held still with a uniform distributor (packing it first when needed).
Settings fixed_bed_settings(const Settings& scene,
                            const std::function<void(const std::string&)>& notify = {});
// The force balance's root (m/s): fixed_bed_lift = 1, by false position from Wen and Yu's
// estimate. `runs` counts the fixed-bed runs.
double force_balance_umf(const Settings& scene, double wen_yu, int& runs,
                         const std::function<void(const std::string&)>& notify = {});

// Measured, or read from the cache (then from `shipped`, a folder of answers; "" for none).
// InputError for a scene without gas.
UmfEstimate estimate_umf(const Settings& scene,
                         const std::function<void(const std::string&)>& notify = {},
                         const std::string& shipped = "");
// An answer file as estimate_umf writes it, read into e (U_mf, how, the branch; from_cache and
// cache_file set); false when the file is missing or not such an answer.
bool read_umf_answer(const std::string& file, UmfEstimate& e);
// U_mf of `changed`, the bed of `scene` with other particles (the viewer's live change), from
// `measured`, `scene`'s own estimate: a measured answer for `changed` in the cache (or in
// `shipped`) when there is one, else measured.umf times the ratio of the two beds' fixed-bed
// force balances (the model's drag on each packed bed, a few seconds of runs). The balance is 13 %
// above the sweep on the paper's bed, for its packed bed is denser than a defluidized one; the
// ratio of two such beds cancels that to first order. InputError as estimate_umf.
UmfEstimate umf_for_particles(const UmfEstimate& measured, const Settings& scene,
                              const Settings& changed,
                              const std::function<void(const std::string&)>& notify = {},
                              const std::string& shipped = "");
// The file name under which estimate_umf keeps `scene`'s answer (umf-HASH.txt); packs the
// scene's bed first when it starts from one not yet cached (the name holds the packing's).
std::string umf_cache_name(const Settings& scene);

}  // namespace fluidbed
