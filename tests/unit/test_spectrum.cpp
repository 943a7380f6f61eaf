// Welch's power spectrum and its dominant frequency, on series with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/spectrum.hpp"
#include "core/errors.hpp"
#include "core/random.hpp"

using fluidbed::PowerSpectrum;
using fluidbed::welch_spectrum;
using fluidbed::WelchSettings;

namespace {

// Standard normal samples (Box-Muller on the platform-independent generator).
std::vector<double> gaussian_noise(std::size_t n, std::uint64_t seed) {
  fluidbed::SplitMix64 rng(seed);
  std::vector<double> v(n);
  for (std::size_t k = 0; k < n; k += 2) {
    const double u = 1.0 - rng.uniform(), w = rng.uniform();
    const double r = std::sqrt(-2.0 * std::log(u));
    v[k] = r * std::cos(2.0 * std::numbers::pi * w);
    if (k + 1 < n) v[k + 1] = r * std::sin(2.0 * std::numbers::pi * w);
  }
  return v;
}

}  // namespace

TEST(Spectrum, FftMatchesTheDirectSum) {
  const std::size_t n = 64;
  std::vector<double> re = gaussian_noise(n, 3), im = gaussian_noise(n, 4);
  const std::vector<double> x_re = re, x_im = im;
  fluidbed::fft_radix2(re, im);
  for (std::size_t k = 0; k < n; ++k) {
    std::complex<double> s = 0.0;
    for (std::size_t t = 0; t < n; ++t)
      s += std::complex<double>(x_re[t], x_im[t]) *
           std::polar(
               1.0, -2.0 * std::numbers::pi * static_cast<double>(k * t) / static_cast<double>(n));
    EXPECT_NEAR(re[k], s.real(), 1e-12);
    EXPECT_NEAR(im[k], s.imag(), 1e-12);
  }
  std::vector<double> bad(6), bad_im(6);
  EXPECT_THROW(fluidbed::fft_radix2(bad, bad_im), std::invalid_argument);
}

TEST(Spectrum, SinePlusNoiseFindsItsFrequencyWithinOneBin) {
  // dp-like: 3550 Pa mean, a 3.7 Hz oscillation of 300 Pa, white noise of 300 Pa (rms) and a
  // slow 0.2 Hz swing of 600 Pa, sampled every millisecond for 12 s; segments of 4 s.
  const double h = 1e-3, f0 = 3.7;
  const auto noise = gaussian_noise(12000, 11);
  std::vector<double> dp(12000);
  for (std::size_t k = 0; k < dp.size(); ++k) {
    const double t = static_cast<double>(k) * h;
    dp[k] = 3550.0 + 300.0 * std::sin(2.0 * std::numbers::pi * f0 * t) + 300.0 * noise[k] +
            600.0 * std::sin(2.0 * std::numbers::pi * 0.2 * t);
  }
  const PowerSpectrum p = welch_spectrum(dp, h);
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.segment_samples, 4000);
  EXPECT_EQ(p.fft_size, 4096);
  EXPECT_EQ(p.segments, 5);  // starts at 0, 2, 4, 6, 8 s
  EXPECT_NEAR(p.df, 1.0 / 4.096, 1e-12);
  EXPECT_NEAR(p.dominant_frequency, f0, p.df);
  EXPECT_NEAR(p.dominant_frequency_refined, f0, 0.25 * p.df);
  // The sine's power (A^2 / 2) is the area under its peak; the noise's (sigma^2) is spread
  // evenly: a density of sigma^2 / f_Nyquist.
  double peak_area = 0.0;
  for (std::size_t b = 0; b < p.psd.size(); ++b)
    if (std::fabs(p.frequency[b] - f0) < 1.5) peak_area += p.psd[b] * p.df;
  EXPECT_NEAR(peak_area, 0.5 * 300.0 * 300.0, 0.1 * 0.5 * 300.0 * 300.0);
  double high = 0.0;
  int bins = 0;
  for (std::size_t b = 0; b < p.psd.size(); ++b)
    if (p.frequency[b] > 50.0) {
      high += p.psd[b];
      ++bins;
    }
  EXPECT_NEAR(high / bins, 300.0 * 300.0 / 500.0, 0.05 * 300.0 * 300.0 / 500.0);
}

TEST(Spectrum, WhiteNoiseDensityIntegratesToItsVariance) {
  const auto v = gaussian_noise(20000, 5);
  const PowerSpectrum p = welch_spectrum(v, 2e-3, WelchSettings{2.0, 0.5, 0.5});
  ASSERT_TRUE(p.ok);
  double total = 0.0;
  for (double d : p.psd) total += d * p.df;
  EXPECT_NEAR(total, 1.0, 0.03);
}

TEST(Spectrum, ShortSeriesIsOneSegmentAndPeaksBelowTheCutAreIgnored) {
  // 1.5 s of a 0.4 Hz wave plus a weaker 6 Hz one: the dominant frequency is the 6 Hz one.
  std::vector<double> y(1500);
  for (std::size_t k = 0; k < y.size(); ++k) {
    const double t = 1e-3 * static_cast<double>(k);
    y[k] = 5.0 * std::sin(2.0 * std::numbers::pi * 0.4 * t) +
           std::sin(2.0 * std::numbers::pi * 6.0 * t);
  }
  const PowerSpectrum p = welch_spectrum(y, 1e-3);
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.segments, 1);
  EXPECT_EQ(p.segment_samples, 1500);
  EXPECT_NEAR(p.dominant_frequency, 6.0, p.df);
  EXPECT_FALSE(welch_spectrum(std::vector<double>(5, 1.0), 1e-3).ok);
  // A constant has no peak.
  EXPECT_EQ(welch_spectrum(std::vector<double>(4000, 2.0), 1e-3).dominant_frequency, 0.0);
  // JSON and CSV.
  const nlohmann::json j = fluidbed::to_json(p);
  EXPECT_NEAR(j["dominant_frequency_hz"].get<double>(), p.dominant_frequency, 1e-15);
  EXPECT_NEAR(j["resolution_hz"].get<double>(), 1.0 / 1.5, 1e-12);
  std::ostringstream os;
  fluidbed::write_spectrum_csv(os, p);
  EXPECT_EQ(os.str().rfind("f,psd\n0,", 0), 0u);
}

TEST(Spectrum, BadSettingsAreInputErrorsNamingTheKey) {
  const std::vector<double> y(100, 0.0);
  const auto expect_key = [&](WelchSettings s, const std::string& key) {
    try {
      welch_spectrum(y, 1e-3, s);
      ADD_FAILURE() << key;
    } catch (const fluidbed::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(key + " ", 0), 0u) << e.what();
    }
  };
  expect_key({0.0, 0.5, 0.5}, "spectrum.segment");
  expect_key({4.0, 1.0, 0.5}, "spectrum.overlap");
  expect_key({4.0, -0.1, 0.5}, "spectrum.overlap");
  expect_key({4.0, 0.5, -1.0}, "spectrum.min_peak_frequency");
  EXPECT_THROW(welch_spectrum(y, 0.0), std::invalid_argument);
}
