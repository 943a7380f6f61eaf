#pragma once
// Reordering per-particle arrays (the particles' renumbering: dem/renumber.cpp).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fluidbed {

// v's groups of `per` values (one group per particle) reordered so that group s is the one that
// was at from[s]; an empty v stays empty.
template <class T>
void gather_by(std::vector<T>& v, const std::vector<std::int32_t>& from, std::size_t per = 1) {
  if (v.empty() || per == 0) return;
  std::vector<T> out(v.size());
  for (std::size_t s = 0; s < from.size(); ++s) {
    const std::size_t f = static_cast<std::size_t>(from[s]) * per;
    for (std::size_t c = 0; c < per; ++c) out[s * per + c] = v[f + c];
  }
  std::copy(out.begin(), out.end(), v.begin());  // v keeps its memory: no heap left behind
}

}  // namespace fluidbed
