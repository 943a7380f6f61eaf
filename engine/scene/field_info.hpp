#pragma once
// What the field table (scene/settings.hpp: visit_fields) says of each scene key besides its
// name: the unit, the values a number may take and one line of help. The validator checks the
// ranges, `fluidbed keys` and the man page print all three, so none of them can drift apart.
#include <limits>
#include <string>
#include <string_view>

namespace fluidbed {

// The values a number may take: from `low` to `high`, each end included unless open. The
// widest range (the default) still asks for a finite number.
struct Range {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool low_open = false;
  bool high_open = false;

  bool bounded_below() const { return low > -std::numeric_limits<double>::infinity(); }
  bool bounded_above() const { return high < std::numeric_limits<double>::infinity(); }
  bool contains(double v) const;
  // "any", "> 0", ">= 0", ">= 3", "(0, 1)", "(0, 1]", "[0, 1)".
  std::string text() const;
};

namespace ranges {
inline constexpr Range any{};
inline constexpr Range positive{0.0, std::numeric_limits<double>::infinity(), true, false};
inline constexpr Range non_negative{0.0, std::numeric_limits<double>::infinity(), false, false};
constexpr Range at_least(double n) {
  return {n, std::numeric_limits<double>::infinity(), false, false};
}
inline constexpr Range open_unit{0.0, 1.0, true, true};       // (0, 1)
inline constexpr Range unit_fraction{0.0, 1.0, true, false};  // (0, 1]: a share that is not 0
inline constexpr Range below_one{0.0, 1.0, false, true};      // [0, 1)
}  // namespace ranges

struct FieldInfo {
  std::string_view unit;  // SI; empty for a pure number, a name, a flag or a path
  Range range;            // numbers only
  std::string_view help;  // one line
};

}  // namespace fluidbed
