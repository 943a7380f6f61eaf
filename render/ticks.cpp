// Tick values and their labels: 1-2-5 steps on linear axes, decades on log axes.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "render/ticks.hpp"

namespace fluidbed::render {

namespace {

constexpr double kEps = 1e-9;  // of a step: a tick this close outside the range still counts

// 10^e as exactly as a double allows (pow can be off by an ulp on some libms).
double pow10(int e) {
  double p = 1.0;
  for (int k = 0; k < std::abs(e); ++k) p *= 10.0;
  return e < 0 ? 1.0 / p : p;
}

// m x 10^e rounded once, so that 3 x 2 x 10^-1 prints as 0.6 and not 0.6000000000000001.
double scaled(double m, int e) {
  return e < 0 ? m / pow10(-e) : m * pow10(e);
}

std::string superscript(int n) {
  static constexpr std::array<const char*, 10> kDigits = {"⁰", "¹", "²", "³", "⁴",
                                                          "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string digits = std::to_string(std::abs(n));
  std::string out = n < 0 ? "⁻" : "";
  for (char c : digits) out += kDigits[static_cast<std::size_t>(c - '0')];
  return out;
}

// Fixed-point with DECIMALS places, a true minus sign, and no "-0".
std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", std::max(0, decimals), v);
  std::string s = buf;
  if (s[0] == '-') {
    if (s.find_first_not_of("-0.") == std::string::npos) return s.substr(1);
    return "−" + s.substr(1);
  }
  return s;
}

// M x 10^E as "M×10ᴱ", or "10ᴱ" when M is 1.
std::string power_label(double m, int e) {
  const std::string mantissa = m == 1.0 ? "" : fixed(m, m == std::round(m) ? 0 : 1) + "×";
  return mantissa + "10" + superscript(e);
}

int floor_log10(double v) {
  return static_cast<int>(std::floor(std::log10(v) + kEps));
}

}  // namespace

Ticks linear_ticks(double lo, double hi, int target) {
  Ticks t;
  if (!std::isfinite(lo) || !std::isfinite(hi)) return t;
  if (!(hi > lo)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", lo);
    t.major = {lo};
    t.labels = {buf[0] == '-' ? "−" + std::string(buf + 1) : std::string(buf)};
    return t;
  }
  target = std::max(target, 2);
  // (hi - lo) itself may overflow.
  const int e0 = static_cast<int>(std::floor(std::log10(hi / target - lo / target)));
  // The 1-2-5 step giving the tick count nearest TARGET; the larger step on a tie.
  double best_m = 1.0;
  int best_e = e0;
  long best_miss = -1;
  for (int e = e0 - 1; e <= e0 + 1; ++e) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double step = scaled(m, e);
      const long count = static_cast<long>(std::floor(hi / step + kEps)) -
                         static_cast<long>(std::ceil(lo / step - kEps)) + 1;
      const long miss = std::abs(count - target);
      if (count >= 2 && (best_miss < 0 || miss <= best_miss)) {
        best_miss = miss;
        best_m = m;
        best_e = e;
      }
    }
  }
  const double step = scaled(best_m, best_e);
  const long k0 = static_cast<long>(std::ceil(lo / step - kEps));
  const long k1 = static_cast<long>(std::floor(hi / step + kEps));
  double largest = 0.0;
  for (long k = k0; k <= k1; ++k) {
    const double v = scaled(static_cast<double>(k) * best_m, best_e);
    t.major.push_back(v);
    largest = std::max(largest, std::abs(v));
  }
  // Labels: as many decimals as the step needs; a shared power of ten when that is over 4 or
  // the numbers reach a million.
  const int decimals = std::max(0, -best_e);
  const int power = largest > 0.0 ? floor_log10(largest) : 0;
  if (decimals > 4 || power >= 6) {
    t.multiplier = "×10" + superscript(power);
    for (double v : t.major) {
      t.labels.push_back(fixed(v / pow10(power), std::max(0, power - best_e)));
    }
  } else {
    for (double v : t.major) t.labels.push_back(fixed(v, decimals));
  }
  return t;
}

Ticks log_ticks(double lo, double hi, int max_major) {
  Ticks t;
  if (!(lo > 0.0) || !(hi > lo) || !std::isfinite(hi)) return t;
  max_major = std::max(max_major, 2);
  const double l0 = std::log10(lo), l1 = std::log10(hi);
  const int d0 = static_cast<int>(std::ceil(l0 - kEps));
  const int d1 = static_cast<int>(std::floor(l1 + kEps));
  const auto inside = [lo, hi](double v) { return v >= lo * (1 - kEps) && v <= hi * (1 + kEps); };
  const int decades = d1 - d0 + 1;
  if (decades >= 2) {
    // Every STRIDE-th decade labelled, the ones between as minor ticks.
    const int stride = (decades + max_major - 1) / max_major;
    for (int d = d0; d <= d1; ++d) {
      if (((d % stride) + stride) % stride == 0) {
        t.major.push_back(pow10(d));
        t.labels.push_back(power_label(1.0, d));
      } else {
        t.minor.push_back(pow10(d));
      }
    }
    if (stride == 1) {
      for (int d = d0 - 1; d <= d1; ++d) {
        for (int m = 2; m <= 9; ++m) {
          const double v = scaled(m, d);
          if (inside(v)) t.minor.push_back(v);
        }
      }
      std::sort(t.minor.begin(), t.minor.end());
    }
    return t;
  }
  // Less than two decades: 1, 2 and 5 x 10^k, the others of 2..9 as minor ticks.
  for (int d = d0 - 1; d <= d1; ++d) {
    for (int m = 1; m <= 9; ++m) {
      const double v = scaled(m, d);
      if (!inside(v)) continue;
      if (m == 1 || m == 2 || m == 5) {
        t.major.push_back(v);
        t.labels.push_back(d < -3 || d >= 5 ? power_label(m, d) : fixed(v, std::max(0, -d)));
      } else {
        t.minor.push_back(v);
      }
    }
  }
  if (t.major.size() < 2) {
    // A narrow range: a linear 1-2-5 scale reads best.
    t = linear_ticks(lo, hi, 3);
  }
  return t;
}

}  // namespace fluidbed::render
