#include "analysis/cycles.hpp"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <cstdio>

namespace fluidbed {

CycleStats analyse_cycles(const std::vector<double>& t, const std::vector<double>& signal,
                          CycleAmplitude against) {
  CycleStats s;
  const std::size_t n = std::min(t.size(), signal.size());
  if (n < 16) return s;
  const double span = t[n - 1] - t[0];
  if (!(span > 0.0)) return s;
  const double h = span / static_cast<double>(n - 1);
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += signal[k];
  mean /= static_cast<double>(n);
  // Detrend (least-squares line) so a slow drift does not show as a low-frequency peak.
  double st = 0.0, stt = 0.0, sty = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double tt = t[k] - t[0];
    st += tt;
    stt += tt * tt;
    sty += tt * (signal[k] - mean);
  }
  const double nn = static_cast<double>(n);
  const double slope = nn * sty / (nn * stt - st * st);  // the mean of y is 0
  const double t_mean = st / nn;
  std::vector<double> y(n);
  for (std::size_t k = 0; k < n; ++k) y[k] = signal[k] - mean - slope * (t[k] - t[0] - t_mean);

  // Power spectrum on a fine frequency grid within the band (and the record's resolution).
  constexpr double kPi = std::numbers::pi;
  const double f_lo = std::max(0.2, 2.0 / span), f_hi = std::min(25.0, 0.25 / h);
  if (!(f_hi > f_lo)) return s;
  const int bins = 600;
  std::vector<double> freq(bins + 1), power(bins + 1);
  double total = 0.0;
  for (int b = 0; b <= bins; ++b) {
    const double f = f_lo * std::pow(f_hi / f_lo, static_cast<double>(b) / bins);
    double re = 0.0, im = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double ph = 2.0 * kPi * f * (t[k] - t[0]);
      re += y[k] * std::cos(ph);
      im += y[k] * std::sin(ph);
    }
    freq[b] = f;
    power[b] = re * re + im * im;
    total += power[b];
  }
  const auto best = static_cast<std::size_t>(
      std::max_element(power.begin(), power.end()) - power.begin());
  const double best_p = power[best], best_f = freq[best];
  s.dominant_period = 1.0 / best_f;
  s.dominant_power_share = total > 0.0 ? best_p / total : 0.0;
  s.amplitude = 2.0 * std::sqrt(best_p) / nn;
  double variance = 0.0;
  for (std::size_t k = 0; k < n; ++k) variance += (signal[k] - mean) * (signal[k] - mean);
  const double base = against == CycleAmplitude::mean ? std::fabs(mean) : std::sqrt(variance / nn);
  const double needed = against == CycleAmplitude::mean ? kAmplitudeShare : kAmplitudeStdShare;
  s.amplitude_share = base != 0.0 ? s.amplitude / base : INFINITY;
  // The spectrum around the peak: the octave either side without the peak's own neighbourhood
  // (a fifth of its frequency, several resolution widths for any peak of kMinCycles or more).
  std::vector<double> around;
  for (int b = 0; b <= bins; ++b) {
    const double r = freq[b] / best_f;
    if ((r >= 0.5 && r <= 1.0 / 1.25) || (r >= 1.25 && r <= 2.0)) around.push_back(power[b]);
  }
  double floor = 0.0;
  if (!around.empty()) {
    std::nth_element(around.begin(), around.begin() + around.size() / 2, around.end());
    floor = around[around.size() / 2];
  }
  s.peak_prominence = floor > 0.0 ? best_p / floor : INFINITY;
  char why[160];
  if (best_f * span < kMinCycles) {
    std::snprintf(why, sizeof why, "no regular cycle: the highest peak (%.3g s) repeats only %.1f times in the record",
                  s.dominant_period, best_f * span);
  } else if (s.peak_prominence < kProminence) {
    std::snprintf(why, sizeof why, "no regular cycle: the highest peak (%.3g s) stands %.1f times above the spectrum around it (%.0f needed)",
                  s.dominant_period, s.peak_prominence, kProminence);
  } else if (s.amplitude_share < needed) {
    std::snprintf(why, sizeof why,
                  "no regular cycle: the oscillation at %.3g s is %.1f %% of the %s (%.0f %% "
                  "needed)",
                  s.dominant_period, 100.0 * s.amplitude_share,
                  against == CycleAmplitude::mean ? "mean" : "standard deviation", 100.0 * needed);
  } else {
    std::snprintf(why, sizeof why, "regular cycle");
    s.regular = true;
  }
  s.verdict = why;

  // Cycle lengths from mean crossings of the smoothed signal.
  const auto half = static_cast<std::size_t>(std::max(1.0, 0.05 * s.dominant_period / h));
  std::vector<double> sm(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k >= half ? k - half : 0, b = std::min(n - 1, k + half);
    double acc = 0.0;
    for (std::size_t q = a; q <= b; ++q) acc += y[q];
    sm[k] = acc / static_cast<double>(b - a + 1);
  }
  double var = 0.0;
  for (double v : sm) var += v * v;
  const double band = 0.25 * std::sqrt(var / nn);
  std::vector<double> ups;
  bool low = sm[0] < -band;
  for (std::size_t k = 1; k < n; ++k) {
    if (low && sm[k] > band) {
      ups.push_back(t[k]);
      low = false;
    } else if (!low && sm[k] < -band) {
      low = true;
    }
  }
  if (ups.size() >= 3) {
    std::vector<double> len;
    for (std::size_t k = 1; k < ups.size(); ++k) len.push_back(ups[k] - ups[k - 1]);
    double m = 0.0;
    for (double l : len) m += l;
    m /= static_cast<double>(len.size());
    double v = 0.0;
    for (double l : len) v += (l - m) * (l - m);
    s.cycles = static_cast<int>(len.size());
    s.cycle_mean = m;
    s.cycle_std = std::sqrt(v / static_cast<double>(len.size()));
    s.cycle_cv = s.cycle_std / m;
  }
  s.ok = true;
  return s;
}

}  // namespace fluidbed
