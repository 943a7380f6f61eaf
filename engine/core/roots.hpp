#pragma once
// A root of f between lo and hi by false position (regula falsi): f(lo) and f(hi) of opposite
// signs; each step replaces the end of the bracket whose value has the sign of the secant's root.
// For functions that cost a simulation each (the fixed bed's force balance against the gas
// velocity): a few evaluations, no derivative.
#include <cmath>

namespace fluidbed {

struct RootBracket {
  double lo = 0.0, hi = 0.0;    // the bracket
  double flo = 0.0, fhi = 0.0;  // f at its ends
  // Where the secant through the ends crosses zero.
  double secant_root() const { return hi - fhi * (hi - lo) / (fhi - flo); }
};

// At most `steps` steps, while hi - lo is wider than `width`.
template <class F>
RootBracket false_position(F&& f, double lo, double hi, int steps, double width) {
  RootBracket b{lo, hi, f(lo), f(hi)};
  for (int k = 0; k < steps && std::fabs(b.hi - b.lo) > width; ++k) {
    const double mid = b.secant_root();
    const double fm = f(mid);
    if ((fm < 0.0) == (b.flo < 0.0)) {
      b.lo = mid;
      b.flo = fm;
    } else {
      b.hi = mid;
      b.fhi = fm;
    }
  }
  return b;
}

}  // namespace fluidbed
