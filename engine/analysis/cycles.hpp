#pragma once
// How regular a pressure-drop signal is (the paper's Figs 16-17: the ideal bed's dp is periodic,
// one bubble forming, growing and bursting before the next).
//   dominant period - the peak of the signal's power spectrum between 0.2 and 25 Hz (a direct
//                     Fourier sum over the detrended samples);
//   cycle lengths   - times between successive upward crossings of the mean by the signal smoothed
//                     over 1/10 of the dominant period, with a hysteresis of a quarter of its
//                     standard deviation so that noise does not count as cycles.
//   regular         - whether the peak is a cycle at all. Every record has a highest peak, noise
//                     and drift included; it counts as a regular cycle only when
//                     (a) it stands kProminence times above the spectrum's median around it (the
//                         octave either side, its own neighbourhood left out), so that a red
//                         spectrum (chaos, drift) is judged against its own slope. Measured on
//                         1,400 records of 6 s at 1 ms of white noise and of red noise
//                         (Ornstein-Uhlenbeck, relaxation times 0.01-0.2 s): the highest peak
//                         stands a median 6-9 times above its surroundings, at most 29 times;
//                     (b) the oscillation's amplitude (of the sinusoid at the peak) is at least
//                         kAmplitudeShare of the signal's mean: a cycle that moves the pressure
//                         drop by a tenth of itself, as the bubble cycle of Fig. 17 does. A
//                         signal whose mean says nothing of its swings (a probe's pressure
//                         against the outlet, whose mean is the weight of the bed above it) is
//                         judged against its standard deviation instead: at least
//                         kAmplitudeStdShare of it, so that the sinusoid carries at least an
//                         eighth of the signal's variance (A^2 / 2 of sigma^2; a pure sine has
//                         A = sqrt 2 sigma, the highest peak of n samples of white noise about
//                         2 sigma sqrt(ln(600) / n), 0.07 sigma at 5,000);
//                     (c) the record holds at least kMinCycles of it (a slower "period" is drift).
#include <string>
#include <vector>

namespace fluidbed {

inline constexpr double kProminence = 40.0;
inline constexpr double kAmplitudeShare = 0.1;
inline constexpr double kAmplitudeStdShare = 0.5;
inline constexpr double kMinCycles = 4.0;

struct CycleStats {
  bool ok = false;                // the record was long and fine enough to analyse
  bool regular = false;           // (a), (b) and (c) above hold: the period means a cycle
  std::string verdict;            // "regular cycle" or "no regular cycle: " and the criterion missed
  double dominant_period = 0.0;   // s, the highest peak's (whether or not it is regular)
  double peak_prominence = 0.0;   // the peak's power over the median around it
  double amplitude = 0.0;         // the sinusoid's amplitude at the peak, in the signal's unit
  double amplitude_share = 0.0;   // amplitude / |mean| (or / std: CycleAmplitude::std)
  double dominant_power_share = 0.0;  // the peak's share of the power in the band
  int cycles = 0;
  double cycle_mean = 0.0;        // s
  double cycle_std = 0.0;         // s
  double cycle_cv = 0.0;          // std / mean: 0 for a perfectly regular cycle
};

// What criterion (b) measures the amplitude against: the signal's mean (dp) or its standard
// deviation (a probe's pressure).
enum class CycleAmplitude { mean, std };

// t must be increasing with a near-constant spacing.
CycleStats analyse_cycles(const std::vector<double>& t, const std::vector<double>& signal,
                          CycleAmplitude against = CycleAmplitude::mean);

}  // namespace fluidbed
