#pragma once
// A record kept as JSON through one list of its fields, read and written by the same function:
// `fields(r, f)` calls f("name", r.member) for each member kept (numbers, bools, strings,
// vectors of them). A double that is not finite is written as null (as JSON has it) and read
// back as NaN. Used for the identity files a command keeps to resume from and for the studies'
// stored points.
#include <cmath>
#include <nlohmann/json.hpp>
#include <type_traits>

namespace fluidbed {

template <class T, class Fields>
nlohmann::json fields_json(const T& r, Fields&& fields) {
  nlohmann::json j = nlohmann::json::object();
  fields(r, [&](const char* name, const auto& v) { j[name] = v; });
  return j;
}

// Reads the fields of `j` into `r`; nlohmann::json's exceptions for a field missing or of
// another type (a double may be null: NaN).
template <class T, class Fields>
void fields_from_json(const nlohmann::json& j, T& r, Fields&& fields) {
  fields(r, [&](const char* name, auto& v) {
    using V = std::decay_t<decltype(v)>;
    if constexpr (std::is_same_v<V, double>)
      v = j.at(name).is_null() ? NAN : j.at(name).template get<double>();
    else
      v = j.at(name).template get<V>();
  });
}

}  // namespace fluidbed
