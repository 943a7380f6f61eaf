#pragma once
// Writing a file so that it is either complete or absent: write to a name of this process's
// own beside it, then rename. A run that fails half-way leaves no half-written result behind, and
// parallel runs writing the same file cannot collide.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "core/errors.hpp"

namespace fluidbed {

// The name this process writes PATH under before renaming it: "PATH.partial.PID".
inline std::string partial_name(const std::string& path) {
  return path + ".partial." + std::to_string(::getpid());
}

// The process that owns a file named as partial_name names it, or nothing when NAME is not such
// a name (a run's own files, or a user's).
inline std::optional<pid_t> partial_owner(const std::string& name) {
  const std::size_t at = name.rfind(".partial.");
  if (at == std::string::npos || at == 0) return std::nullopt;
  const std::string digits = name.substr(at + 9);
  if (digits.empty() || digits.size() > 9 ||
      digits.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return static_cast<pid_t>(std::stol(digits));
}

template <class Writer>
void write_file_atomically(const std::string& path, Writer&& write) {
  const std::string tmp = partial_name(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError("cannot write " + path);
    write(out);
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw InputError("cannot write " + path);
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError("cannot write " + path);
  }
}

}  // namespace fluidbed
