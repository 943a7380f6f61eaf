#pragma once
// Writing a file so that it is either complete or absent: write to a name of this process's
// own beside it, then rename. A run that fails half-way leaves no half-written result behind, and
// parallel runs writing the same file cannot collide.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "core/errors.hpp"

namespace fluidbed {

template <class Writer>
void write_file_atomically(const std::string& path, Writer&& write) {
  const std::string tmp = path + ".partial." + std::to_string(::getpid());
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
