#pragma once
// Opening a file the user named (a scene, a viewer script, a state file): anything but a
// readable regular file (a directory, a device, a pipe, a file without read permission, a
// missing one) is an InputError of one line naming the file and what it is, before a byte is
// read. A directory opens as an empty stream on Linux, so without this a folder given as a scene
// would run the default bed.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.hpp"

namespace fluidbed {

// `what`: "scene file", "state file", "script". The stream is open at the file's start.
inline std::ifstream open_input_file(const std::string& path, const std::string& what,
                                     std::ios::openmode mode = std::ios::binary) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symbolic links
  const std::string head = "cannot read " + what + " " + path + ": ";
  if (ec || !fs::exists(st)) throw InputError(head + "no such file");
  if (fs::is_directory(st)) throw InputError(head + "it is a directory");
  if (!fs::is_regular_file(st))
    throw InputError(head + "it is not a regular file (a device or a pipe)");
  std::ifstream in(path, mode);
  if (!in) throw InputError(head + std::strerror(errno));
  return in;
}

}  // namespace fluidbed
