#pragma once
// Numbers and fields as text, one way for the whole program: tables, reports, decks and messages.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace fluidbed {

// printf of one number with `format` (one conversion, e.g. "%.3g m/s"); "n/a" where the value
// is not finite and `missing` is not given.
inline std::string format_number(const char* format, double v, const char* missing = nullptr) {
  if (missing && !std::isfinite(v)) return missing;
  char b[128];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

// A table's number: %.6g, and empty where there is none (NaN: a failed point's value).
inline std::string table_number(double v) {
  return format_number("%.6g", v, "");
}

// The shortest text that reads back as the same double (a deck holds exactly the scene's
// numbers).
inline std::string shortest_number(double v) {
  char b[32];
  const auto r = std::to_chars(b, b + sizeof b, v, std::chars_format::general);
  return std::string(b, r.ptr);
}

// One CSV field: newlines become spaces; quoted (with quotes doubled) when it holds a comma or a
// quote.
inline std::string csv_field(std::string s) {
  for (char& c : s)
    if (c == '\n') c = ' ';
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace fluidbed
