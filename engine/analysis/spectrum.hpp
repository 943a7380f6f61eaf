#pragma once
// Welch's estimate of the power spectral density of a uniformly sampled series (model.md 6: the
// spectrum of dp): the series is cut into segments of `segment` seconds overlapping by `overlap`
// of their length; each segment has its mean removed, is multiplied by a Hann window and
// transformed; the squared magnitudes are averaged over the segments and scaled to a one-sided
// density (unit^2/Hz: the integral over 0..f_Nyquist is the series' variance, to within the
// window's leakage). A series shorter than one segment is one segment of its own length.
//
// The transform: a radix-2 FFT written here (no dependency), the segment zero-padded to the next
// power of two. Padding does not sharpen the resolution (1 / segment length) but samples the
// spectrum more finely; the bin spacing `df` reported is the padded one.
//
// Dominant frequency: the largest local maximum of the density above min_peak_frequency (0.5 Hz
// by default: slower content is drift, not bubbles), refined by a parabola through the peak bin
// and its neighbours (in the logarithm of the density: exact for a Gaussian peak, which is what
// a Hann window makes of a sine).
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fluidbed {

struct WelchSettings {
  double segment = 4.0;             // s, segment length ("a few seconds")
  double overlap = 0.5;             // -, share of a segment overlapping the next; [0, 1)
  double min_peak_frequency = 0.5;  // Hz, the dominant frequency is sought above this
};

struct PowerSpectrum {
  bool ok = false;                          // false: fewer than 8 samples
  double sample_interval = 0.0;             // s
  int segment_samples = 0;                  // samples per segment (before padding)
  int fft_size = 0;                         // padded length (a power of two)
  int segments = 0;                         // averaged
  double df = 0.0;                          // Hz, bin spacing: 1 / (fft_size x sample_interval)
  std::vector<double> frequency;            // Hz, 0 .. Nyquist
  std::vector<double> psd;                  // unit^2/Hz, one-sided
  double dominant_frequency = 0.0;          // Hz, the peak bin's frequency (0: no peak)
  double dominant_frequency_refined = 0.0;  // Hz, parabola through the peak (0: no peak)
  double dominant_psd = 0.0;                // unit^2/Hz at the peak bin
};

// Throws InputError naming `spectrum.segment` / `spectrum.overlap` /
// `spectrum.min_peak_frequency` for impossible settings, and std::invalid_argument for a
// sample interval that is not positive.
PowerSpectrum welch_spectrum(const std::vector<double>& series, double sample_interval,
                             const WelchSettings& s = {});

// In-place radix-2 FFT of (re, im), size a power of two (exp(-2 pi i k n / N), unscaled).
void fft_radix2(std::vector<double>& re, std::vector<double>& im);

// {"dominant_frequency_hz", "dominant_frequency_refined_hz", "resolution_hz", "bin_hz",
//  "segments", "segment_s", "sample_interval_s"} (the arrays go to a CSV).
nlohmann::json to_json(const PowerSpectrum& p);
// Another spectrum of the same bins, as a further column of the CSV (its name in the header).
struct SpectrumColumn {
  std::string name;
  const PowerSpectrum* spectrum = nullptr;
};

// "f,psd\n" then one row per bin; with `more`, a column of each after psd (a spectrum of other
// bins leaves its cells empty where it has none).
void write_spectrum_csv(std::ostream& out, const PowerSpectrum& p,
                        const std::vector<SpectrumColumn>& more = {});

}  // namespace fluidbed
