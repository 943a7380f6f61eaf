#pragma once
// How regular a pressure-drop signal is (the paper's Figs 16-17: the ideal bed's dp is periodic,
// one bubble forming, growing and bursting before the next).
//   dominant period - the peak of the signal's power spectrum between 0.2 and 25 Hz (a direct
//                     Fourier sum over the detrended samples);
//   cycle lengths   - times between successive upward crossings of the mean by the signal smoothed
//                     over 1/10 of the dominant period, with a hysteresis of a quarter of its
//                     standard deviation so that noise does not count as cycles.
#include <vector>

namespace fluidbed {

struct CycleStats {
  bool ok = false;
  double dominant_period = 0.0;   // s
  double dominant_power_share = 0.0;  // the peak's share of the power in the band
  int cycles = 0;
  double cycle_mean = 0.0;        // s
  double cycle_std = 0.0;         // s
  double cycle_cv = 0.0;          // std / mean: 0 for a perfectly regular cycle
};

// t must be increasing with a near-constant spacing.
CycleStats analyse_cycles(const std::vector<double>& t, const std::vector<double>& signal);

}  // namespace fluidbed
