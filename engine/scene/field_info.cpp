#include "scene/field_info.hpp"

#include <cmath>
#include <cstdio>

namespace fluidbed {

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool above = low_open ? v > low : v >= low;
  const bool below = high_open ? v < high : v <= high;
  return above && below;
}

std::string Range::text() const {
  char buf[64];
  if (!bounded_below() && !bounded_above()) return "any";
  if (!bounded_above()) {
    std::snprintf(buf, sizeof buf, "%s %g", low_open ? ">" : ">=", low);
  } else if (!bounded_below()) {
    std::snprintf(buf, sizeof buf, "%s %g", high_open ? "<" : "<=", high);
  } else {
    std::snprintf(buf, sizeof buf, "%c%g, %g%c", low_open ? '(' : '[', low, high,
                  high_open ? ')' : ']');
  }
  return buf;
}

}  // namespace fluidbed
