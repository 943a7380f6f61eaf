#pragma once
// Raw little helpers for the binary state files: values and arrays written as their bytes, read
// back with checks that name the file when it is truncated or inconsistent.
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace fluidbed {

template <class T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T>
void put_vec(std::ostream& out, const std::vector<T>& v) {
  put(out, static_cast<std::uint64_t>(v.size()));
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(v.size() * sizeof(T)));
}

class BinarySource {
 public:
  BinarySource(std::istream& in, const std::string& origin) : in_(in), origin_(origin) {}

  template <class T>
  T get() {
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof(T));
    if (!in_) fail("truncated");
    return v;
  }
  // An array whose length must be `expected` (any length when expected < 0).
  template <class T>
  void get_vec(std::vector<T>& v, std::int64_t expected = -1) {
    const auto n = get<std::uint64_t>();
    if (expected >= 0 && n != static_cast<std::uint64_t>(expected)) fail("inconsistent (array sizes)");
    if (n > (1ULL << 34) / sizeof(T)) fail("inconsistent (array too large)");
    v.resize(n);
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    if (!in_) fail("truncated");
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(origin_ + ": state file is " + what);
  }
  std::istream& stream() { return in_; }
  const std::string& origin() const { return origin_; }

 private:
  std::istream& in_;
  const std::string& origin_;
};

}  // namespace fluidbed
