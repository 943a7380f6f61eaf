#include "render/asset_dir.hpp"

#include <cstdlib>
#include <system_error>

namespace fluidbed::render {

std::string source_asset_dir() {
  return FLUIDBED_SOURCE_ASSET_DIR;
}

std::string find_asset_dir(const char* env, const std::filesystem::path& program) {
  if (env != nullptr && *env != '\0') return env;
  if (!program.empty()) {
    // FLUIDBED_INSTALLED_ASSET_DIR is the share folder relative to the installed program's
    // folder (CMake's install layout, e.g. "../share/fluidbed").
    const std::filesystem::path share = program.parent_path() / FLUIDBED_INSTALLED_ASSET_DIR;
    std::error_code ec;
    if (std::filesystem::is_directory(share / "scenes", ec)) {
      const std::filesystem::path clean = std::filesystem::weakly_canonical(share, ec);
      return (ec ? share : clean).string();
    }
  }
  return source_asset_dir();
}

std::string asset_dir() {
  std::error_code ec;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
  return find_asset_dir(std::getenv("FLUIDBED_ASSETS"), ec ? std::filesystem::path() : program);
}

std::string find_doc_dir(const std::filesystem::path& program) {
  std::error_code ec;
  if (!program.empty()) {
    const std::filesystem::path installed = program.parent_path() / FLUIDBED_INSTALLED_DOC_DIR;
    if (std::filesystem::is_regular_file(installed / "README.md", ec)) {
      const std::filesystem::path clean = std::filesystem::weakly_canonical(installed, ec);
      return (ec ? installed : clean).string();
    }
  }
  const std::filesystem::path source = FLUIDBED_SOURCE_DOC_DIR;
  if (std::filesystem::is_regular_file(source / "README.md", ec) &&
      std::filesystem::is_directory(source / "docs", ec))
    return source.string();
  return {};
}

std::string doc_dir() {
  std::error_code ec;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
  return find_doc_dir(ec ? std::filesystem::path() : program);
}

}  // namespace fluidbed::render
