#pragma once
// One scene value in TOML syntax, as the resolved-scene writer and `fluidbed keys` print it.
// Engine-internal: it includes toml++, which only the scene's .cpp files see.
#include <concepts>
#include <sstream>
#include <string>
#include <toml++/toml.h>

#include "scene/options.hpp"
#include "scene/settings.hpp"

namespace fluidbed {

inline std::string toml_value(const std::string& v) {
  std::ostringstream out;
  out << toml::value<std::string>(v);
  return out.str();
}
inline std::string toml_value(bool v) { return v ? "true" : "false"; }
inline std::string toml_value(double v) {
  std::ostringstream out;
  out << toml::value<double>(v);
  return out.str();
}
template <std::integral I>
std::string toml_value(I v) {
  return std::to_string(v);
}
template <class E>
  requires is_option_v<E>
std::string toml_value(E v) {
  return toml_value(option_string(v));
}
// Points as an array of [x, y] arrays: [[0.045, 0.045], [0.075, 0.1]]; none: [].
inline std::string toml_value(const std::vector<ProbePoint>& points) {
  std::string out = "[";
  for (const ProbePoint& p : points)
    out += (out.size() > 1 ? ", [" : "[") + toml_value(p.x) + ", " + toml_value(p.y) + "]";
  return out + "]";
}

}  // namespace fluidbed
