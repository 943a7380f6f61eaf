// The teaching scene (what `fluidbed view` opens) against the paper-fidelity bed: the cheaper
// settings must leave the bed's behaviour within the bounds it was chosen for (mean dp within
// 5 %, dominant frequency of dp (Welch) within 10 %, mean bed height within 5 %, max overlap
// after start-up below 4 % (0.16 mm of a 4 mm sphere, under a pixel in any frame the program
// draws), mean bubble diameter and eruption frequency within 15 %), over 6 s from the same
// packed bed, averages from 1 s. The two runs go side by side on two threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <thread>

#include "scene/scene_loader.hpp"
#include "run/run_loop.hpp"
#include "sim/simulation.hpp"
#include "run/packed_bed.hpp"

using namespace fluidbed;

namespace {

nlohmann::json run_scene(const std::string& name, double until) {
  Settings s = load_scene(std::string(FLUIDBED_ASSET_DIR) + "/scenes/" + name);
  prepare_packed_bed(s);
  Simulation sim(s);
  RunOptions o;
  o.until = until;
  o.bubbles = until > 0.0;
  return run_simulation(sim, o).summary;
}

}  // namespace

TEST(TeachingScene, BehavesLikeThePaperFidelityBed) {
  nlohmann::json paper, teaching;
  // The paper's packing is made (or found in the cache) first, so the two runs do not race for it.
  (void)run_scene("xu_yu_1997.toml", 0.0);
  std::thread t([&] { teaching = run_scene("teaching.toml", 6.0); });
  paper = run_scene("xu_yu_1997.toml", 6.0);
  t.join();
  auto rel = [&](const nlohmann::json& a, const nlohmann::json& b) {
    return a.get<double>() / b.get<double>() - 1.0;
  };
  const double dp = rel(teaching["dp_mean_pa"], paper["dp_mean_pa"]);
  const double f = rel(teaching["dp_spectrum"]["dominant_frequency_refined_hz"],
                       paper["dp_spectrum"]["dominant_frequency_refined_hz"]);
  const double h = rel(teaching["bed_height_mean_m"], paper["bed_height_mean_m"]);
  const double d_eq = rel(teaching["bubbles"]["mean_d_eq_m"], paper["bubbles"]["mean_d_eq_m"]);
  const double eruptions =
      rel(teaching["bubbles"]["eruptions_per_s"], paper["bubbles"]["eruptions_per_s"]);
  const double overlap = teaching["max_overlap_ratio_after_startup"].get<double>();
  const double cost = paper["wall_s_per_sim_s"].get<double>() / teaching["wall_s_per_sim_s"].get<double>();
  std::printf("teaching vs paper: mean dp %+.2f %%, dominant frequency %+.2f %%, bed height %+.2f %%, "
              "max overlap after start-up %.2f %% (paper %.2f %%), mean bubble diameter %+.2f %%, "
              "eruption frequency %+.2f %%, %.1f times cheaper\n",
              100 * dp, 100 * f, 100 * h, 100 * overlap,
              100 * paper["max_overlap_ratio_after_startup"].get<double>(), 100 * d_eq,
              100 * eruptions, cost);
  EXPECT_LT(std::fabs(dp), 0.05);
  EXPECT_LT(std::fabs(f), 0.10);
  EXPECT_LT(std::fabs(h), 0.05);
  EXPECT_LT(overlap, 0.04);
  EXPECT_LT(std::fabs(d_eq), 0.15);
  EXPECT_LT(std::fabs(eruptions), 0.15);
}
