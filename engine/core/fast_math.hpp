#pragma once
// exp and log for the hot loops (the drag law takes one log and two exps per particle per step,
// which with libm's calls was the largest single cost of a coupled step). Written as plain
// arithmetic and bit operations, with no call and no branch, so the compiler inlines them and
// can vectorise the loop around them. Accuracy: within 2 units in the last place of libm's
// results on their domains (tests/unit/test_fast_math.cpp checks 1e6 samples each); the
// results are the same bits on every machine and for every thread count.
#include <bit>
#include <cstdint>

namespace fluidbed {

// e^x for -708 <= x <= 709 (no check: the drag law's arguments lie within about [-500, 15];
// a check would be a branch, and no loop with one vectorises). Range reduction x = k ln 2 + r with |r| <= ln 2 / 2 (Cody-Waite, two-part
// ln 2), then e^r by its Taylor series to r^13 (truncation below 1e-17 relative), then 2^k put
// into the exponent bits.
inline double fast_exp(double x) {
  constexpr double kLog2e = 1.4426950408889634074;
  constexpr double kLn2Hi = 6.93147180369123816490e-01;  // ln 2, upper 32 bits
  constexpr double kLn2Lo = 1.90821492927058770002e-10;  // ln 2 - kLn2Hi
  constexpr double kShift = 6755399441055744.0;          // 1.5 * 2^52: rounds to an integer
  // Adding 1.5 * 2^52 rounds x / ln 2 to the nearest integer k and leaves k in the low bits of
  // the sum (integer adds and shifts only, so the loop around it vectorises).
  const double shifted = x * kLog2e + kShift;
  const double kd = shifted - kShift;
  const double r = (x - kd * kLn2Hi) - kd * kLn2Lo;
  // e^r = 1 + r + r^2/2! + ... + r^13/13!, Horner.
  double p = 1.0 / 6227020800.0;
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^k: k + 1023 into the exponent field (k is in the sum's low bits, two's complement).
  const std::uint64_t kbits = std::bit_cast<std::uint64_t>(shifted) + 1023;
  const double scale = std::bit_cast<double>(kbits << 52);
  return p * scale;
}

// ln x for positive normal x (no zero, infinity, NaN or subnormal: the drag law floors its
// argument at 1e-30). x = 2^e m with sqrt(1/2) <= m < sqrt(2); ln m = 2 atanh(s),
// s = (m - 1) / (m + 1), |s| <= 0.172, by its series to s^21 (truncation below 1e-18).
inline double fast_log(double x) {
  constexpr double kLn2Hi = 6.93147180369123816490e-01;
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  constexpr std::uint64_t kSqrtHalfBits = 0x3fe6a09e667f3bcdULL;  // sqrt(1/2)
  const auto bits = std::bit_cast<std::uint64_t>(x);
  // Shift so that the mantissa lands in [sqrt(1/2), sqrt(2)): subtract the bits of sqrt(1/2),
  // take the exponent of that, and put the rest back on sqrt(1/2)'s exponent.
  const std::uint64_t t = bits - kSqrtHalfBits;
  // The exponent e is the top 12 bits of t as a signed number: offset by 2048 into [0, 4096)
  // with integer adds and a mask, turned into a double by the 2^52 trick, offset back (SSE2
  // has no 64-bit arithmetic shift or integer-to-double conversion; this needs neither).
  constexpr double kTwo52 = 4503599627370496.0;
  const std::uint64_t biased = ((t >> 52) + 2048) & 0xfff;
  const double ed =
      std::bit_cast<double>(biased | std::bit_cast<std::uint64_t>(kTwo52)) - (kTwo52 + 2048.0);
  const double m = std::bit_cast<double>(bits - (t & 0xfff0000000000000ULL));
  const double f = m - 1.0;
  const double s = f / (2.0 + f);
  const double s2 = s * s;
  double q = 1.0 / 21.0;
  q = q * s2 + 1.0 / 19.0;
  q = q * s2 + 1.0 / 17.0;
  q = q * s2 + 1.0 / 15.0;
  q = q * s2 + 1.0 / 13.0;
  q = q * s2 + 1.0 / 11.0;
  q = q * s2 + 1.0 / 9.0;
  q = q * s2 + 1.0 / 7.0;
  q = q * s2 + 1.0 / 5.0;
  q = q * s2 + 1.0 / 3.0;
  // ln m = 2 s + 2 s^3 q = f - s f + 2 s^3 q (2 s = f - s f), which keeps f exact up front.
  const double ln_m = f - s * f + 2.0 * s * s2 * q;
  return ed * kLn2Hi + (ln_m + ed * kLn2Lo);
}

}  // namespace fluidbed
