#pragma once
// Saved state as bytes: the binary state files and a run's checkpoint.
//
// One convention for every class whose state is saved: a single member template lists its fields
// once, in order, and serves both directions,
//
//   template <class Archive>
//   void fields(Archive& a) { a(first_step_, rows_, bounces_); }
//
//   void save(BinarySink& out) const { const_cast<X*>(this)->fields(out); }   // or save_fields
//   void restore(BinarySource& in) { fields(in); }
//
// A field is a trivially copyable value (written as its bytes; bool as one byte), a std::vector
// of them (its length, then its elements), a std::vector of a class that has fields() itself, such
// a class, or a std::optional of any of these (a flag, then the value; read back, the optional
// must already be engaged or not as it was saved: the object is built for the same run).
// BinarySink writes; BinarySource reads the same list back with checks that name the file when it
// is truncated or inconsistent. `tag` marks a section with its
// name and version: a file written by another version is refused in one line. Both archives take
// the same calls, so that a class's fields() may hold its tag and its checks too, and holds them
// wherever it is saved (on its own or as a field of another):
//
//   template <class Archive>
//   void fields(Archive& a) {
//     a.tag("FLBTRK02", "bubble tracker");
//     a(has_prev_, label_);
//     a.check(!has_prev_ || label_.size() == cells, "array sizes");  // read back: refused
//   }
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <type_traits>
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

namespace binary_detail {
template <class T, class A>
concept HasFields = requires(T& t, A& a) { t.fields(a); };
template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};
template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};
}  // namespace binary_detail

// Writes fields (see the convention above).
class BinarySink {
 public:
  explicit BinarySink(std::ostream& out) : out_(out) {}

  template <class... T>
  void operator()(const T&... v) {
    (write(v), ...);
  }
  // A section's name and version, at most 8 characters ("FLBREC05").
  void tag(const char* name) {
    char t[8] = {};
    std::memcpy(t, name, std::min<std::size_t>(std::strlen(name), sizeof t));
    out_.write(t, sizeof t);
  }
  // The same, in the form fields() calls for both archives (what: the section's name in words).
  void tag(const char* name, const char* /*what*/) { tag(name); }
  // A consistency check of what is read back (BinarySource::check); nothing to do when writing.
  void check(bool /*ok*/, const char* /*what*/) {}
  std::ostream& stream() { return out_; }

 private:
  template <class T>
  void write(const T& v) {
    if constexpr (binary_detail::HasFields<T, BinarySink>) {
      const_cast<T&>(v).fields(*this);
    } else if constexpr (binary_detail::IsVector<T>::value) {
      using E = typename T::value_type;
      if constexpr (std::is_trivially_copyable_v<E> && !binary_detail::HasFields<E, BinarySink>) {
        put_vec(out_, v);
      } else {
        put(out_, static_cast<std::uint64_t>(v.size()));
        for (const E& e : v) write(e);
      }
    } else if constexpr (binary_detail::IsOptional<T>::value) {
      put(out_, static_cast<std::uint8_t>(v.has_value()));
      if (v) write(*v);
    } else if constexpr (std::is_same_v<T, bool>) {
      put(out_, static_cast<std::uint8_t>(v));
    } else {
      static_assert(std::is_trivially_copyable_v<T>, "a saved field must be plain bytes or have fields()");
      put(out_, v);
    }
  }

  std::ostream& out_;
};

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

  // Reads fields back (see the convention above).
  template <class... T>
  void operator()(T&... v) {
    (read(v), ...);
  }
  // Checks a section's tag: another version of the same section (the first 6 characters alike)
  // is refused as written by another version of fluidbed, anything else as not `what`.
  void tag(const char* name, const char* what) {
    char want[8] = {}, got[8] = {};
    std::memcpy(want, name, std::min<std::size_t>(std::strlen(name), sizeof want));
    in_.read(got, sizeof got);
    if (in_ && std::memcmp(got, want, sizeof got) == 0) return;
    if (in_ && std::memcmp(got, want, 6) == 0)
      fail("written by another version of fluidbed (" + std::string(what) + " " +
           std::string(got + 6, 2) + ", this one reads " + std::string(want + 6, 2) +
           "): run it again from its start");
    fail(std::string("not a ") + what + "'s");
  }
  // Refuses the file as inconsistent (`what`: which part) unless ok.
  void check(bool ok, const char* what) {
    if (!ok) fail(std::string("inconsistent (") + what + ")");
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(origin_ + ": state file is " + what);
  }
  std::istream& stream() { return in_; }
  const std::string& origin() const { return origin_; }

 private:
  template <class T>
  void read(T& v) {
    if constexpr (binary_detail::HasFields<T, BinarySource>) {
      v.fields(*this);
    } else if constexpr (binary_detail::IsVector<T>::value) {
      using E = typename T::value_type;
      if constexpr (std::is_trivially_copyable_v<E> && !binary_detail::HasFields<E, BinarySource>) {
        get_vec(v);
      } else {
        const auto n = get<std::uint64_t>();
        if (n > (1ULL << 28)) fail("inconsistent (array too large)");
        v.assign(n, E{});
        for (E& e : v) read(e);
      }
    } else if constexpr (binary_detail::IsOptional<T>::value) {
      const bool has = get<std::uint8_t>() != 0;
      if (has != v.has_value()) fail("inconsistent (a part saved that this run does not have, or the reverse)");
      if (v) read(*v);
    } else if constexpr (std::is_same_v<T, bool>) {
      v = get<std::uint8_t>() != 0;
    } else {
      static_assert(std::is_trivially_copyable_v<T>, "a saved field must be plain bytes or have fields()");
      v = get<T>();
    }
  }

  std::istream& in_;
  std::string origin_;  // a copy: a source may outlive the string it was named with
};

}  // namespace fluidbed
