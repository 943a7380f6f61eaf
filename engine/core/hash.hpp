#pragma once
// FNV-1a over raw bytes: the state hash that proves determinism (same scene, seed and thread
// count give the same bits).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

namespace fluidbed {

class Fnv1a {
 public:
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h_ ^= p[i];
      h_ *= 1099511628211ULL;
    }
  }
  template <class T>
  void values(const std::vector<T>& v) {
    bytes(v.data(), v.size() * sizeof(T));
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof(T));
  }
  std::uint64_t digest() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ULL;
};

// The FNV-1a hash of some bytes as 16 hex digits.
inline std::string hex_digest(const std::string& bytes) {
  Fnv1a h;
  h.bytes(bytes.data(), bytes.size());
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h.digest()));
  return b;
}

// The same of a file's bytes; empty when it cannot be read.
inline std::string file_digest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  return hex_digest(
      std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
}

}  // namespace fluidbed
