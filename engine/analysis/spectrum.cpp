#include "analysis/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace fluidbed {

void fft_radix2(std::vector<double>& re, std::vector<double>& im) {
  const std::size_t n = re.size();
  if (n != im.size() || (n & (n - 1)) != 0)
    throw std::invalid_argument("fft_radix2: size must be a power of two");
  // Bit-reversal permutation, then butterflies; the twiddles of each stage by a recurrence from
  // one cos/sin pair (relative error ~ log2(n) x 1e-16, ample for a spectrum).
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) {
      std::swap(re[i], re[j]);
      std::swap(im[i], im[j]);
    }
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = -2.0 * std::numbers::pi / static_cast<double>(len);
    const double wr = std::cos(angle), wi = std::sin(angle);
    for (std::size_t i = 0; i < n; i += len) {
      double cr = 1.0, ci = 0.0;
      for (std::size_t k = 0; k < len / 2; ++k) {
        const std::size_t a = i + k, b = i + k + len / 2;
        const double tr = re[b] * cr - im[b] * ci;
        const double ti = re[b] * ci + im[b] * cr;
        re[b] = re[a] - tr;
        im[b] = im[a] - ti;
        re[a] += tr;
        im[a] += ti;
        const double nr = cr * wr - ci * wi;
        ci = cr * wi + ci * wr;
        cr = nr;
      }
    }
  }
}

PowerSpectrum welch_spectrum(const std::vector<double>& series, double h, const WelchSettings& s) {
  if (!(s.segment > 0.0) || !std::isfinite(s.segment)) {
    std::ostringstream os;
    os << "spectrum.segment must be positive (got " << s.segment << " s)";
    throw InputError(os.str());
  }
  if (!(s.overlap >= 0.0 && s.overlap < 1.0)) {
    std::ostringstream os;
    os << "spectrum.overlap must be in [0, 1) (got " << s.overlap << ")";
    throw InputError(os.str());
  }
  if (!(s.min_peak_frequency >= 0.0)) {
    std::ostringstream os;
    os << "spectrum.min_peak_frequency must not be negative (got " << s.min_peak_frequency
       << " Hz)";
    throw InputError(os.str());
  }
  if (!(h > 0.0)) throw std::invalid_argument("welch_spectrum: sample interval must be positive");

  PowerSpectrum out;
  out.sample_interval = h;
  const std::size_t n = series.size();
  if (n < 8) return out;
  const auto wanted = static_cast<std::size_t>(std::max(8.0, std::round(s.segment / h)));
  const std::size_t m = std::min(n, wanted);
  // Segment starts: step (1 - overlap) m, the last segment ending at or before the end.
  const auto step = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::llround((1.0 - s.overlap) * static_cast<double>(m))));
  std::size_t nfft = 1;
  while (nfft < m) nfft <<= 1;

  // Hann window (the periodic form, so that half-overlapped windows sum to a constant).
  std::vector<double> w(m);
  double w2 = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    w[k] = 0.5 -
           0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(m));
    w2 += w[k] * w[k];
  }
  const std::size_t bins = nfft / 2 + 1;
  std::vector<double> acc(bins, 0.0), re(nfft), im(nfft);
  int segments = 0;
  for (std::size_t start = 0; start + m <= n; start += step) {
    double mean = 0.0;
    for (std::size_t k = 0; k < m; ++k) mean += series[start + k];
    mean /= static_cast<double>(m);
    std::fill(re.begin(), re.end(), 0.0);
    std::fill(im.begin(), im.end(), 0.0);
    for (std::size_t k = 0; k < m; ++k) re[k] = (series[start + k] - mean) * w[k];
    fft_radix2(re, im);
    for (std::size_t b = 0; b < bins; ++b) acc[b] += re[b] * re[b] + im[b] * im[b];
    ++segments;
  }
  // One-sided density: |X|^2 / (fs sum w^2), doubled except at 0 and Nyquist.
  const double scale = h / (w2 * segments);
  out.ok = true;
  out.segment_samples = static_cast<int>(m);
  out.fft_size = static_cast<int>(nfft);
  out.segments = segments;
  out.df = 1.0 / (static_cast<double>(nfft) * h);
  out.frequency.resize(bins);
  out.psd.resize(bins);
  for (std::size_t b = 0; b < bins; ++b) {
    out.frequency[b] = static_cast<double>(b) * out.df;
    const bool edge = b == 0 || b == nfft / 2;
    out.psd[b] = acc[b] * scale * (edge ? 1.0 : 2.0);
  }

  // The largest local maximum above the cut.
  std::size_t best = 0;
  for (std::size_t b = 1; b + 1 < bins; ++b) {
    if (out.frequency[b] <= s.min_peak_frequency) continue;
    if (out.psd[b] > out.psd[b - 1] && out.psd[b] >= out.psd[b + 1] &&
        (best == 0 || out.psd[b] > out.psd[best]))
      best = b;
  }
  if (best > 0) {
    out.dominant_frequency = out.frequency[best];
    out.dominant_psd = out.psd[best];
    const double a = std::log(std::max(out.psd[best - 1], 1e-300));
    const double c = std::log(std::max(out.psd[best], 1e-300));
    const double d = std::log(std::max(out.psd[best + 1], 1e-300));
    const double denom = a - 2.0 * c + d;
    const double shift = denom < 0.0 ? std::clamp(0.5 * (a - d) / denom, -0.5, 0.5) : 0.0;
    out.dominant_frequency_refined = (static_cast<double>(best) + shift) * out.df;
  }
  return out;
}

nlohmann::json to_json(const PowerSpectrum& p) {
  nlohmann::json j;
  const auto peak = [&](double f) { return f > 0.0 ? nlohmann::json(f) : nlohmann::json(nullptr); };
  j["dominant_frequency_hz"] = peak(p.dominant_frequency);
  j["dominant_frequency_refined_hz"] = peak(p.dominant_frequency_refined);
  j["resolution_hz"] = p.segment_samples > 0 ? 1.0 / (p.segment_samples * p.sample_interval) : 0.0;
  j["bin_hz"] = p.df;
  j["segments"] = p.segments;
  j["segment_s"] = p.segment_samples * p.sample_interval;
  j["sample_interval_s"] = p.sample_interval;
  return j;
}

void write_spectrum_csv(std::ostream& out, const PowerSpectrum& p,
                        const std::vector<SpectrumColumn>& more) {
  out << "f,psd";
  for (const SpectrumColumn& c : more) out << "," << c.name;
  out << "\n";
  char buf[64];
  for (std::size_t b = 0; b < p.frequency.size(); ++b) {
    int n = std::snprintf(buf, sizeof buf, "%.9g,%.9g", p.frequency[b], p.psd[b]);
    out.write(buf, n);
    for (const SpectrumColumn& c : more) {
      const bool has = c.spectrum->psd.size() == p.psd.size();
      n = has ? std::snprintf(buf, sizeof buf, ",%.9g", c.spectrum->psd[b]) : 1;
      out.write(has ? buf : ",", n);
    }
    out << "\n";
  }
}

}  // namespace fluidbed
