#pragma once
// Where the shipped assets are (scenes/, fonts/ and any later folder such as lessons/): one rule
// for every part of the program that reads them, the font lookup included (render/font_file.hpp).
#include <filesystem>
#include <string>

namespace fluidbed::render {

// The assets folder, the first of: $FLUIDBED_ASSETS when set and not empty; the share folder of
// an installed copy, found from the running program's own path (PREFIX/bin/fluidbed ->
// PREFIX/share/fluidbed) when it holds scenes/; the source tree's assets/ (the program run from
// its build folder).
std::string asset_dir();

// The same rule over given inputs: `env` the variable's value (null: unset), `program` the
// running program's path (empty: unknown). asset_dir() is this with the real ones.
std::string find_asset_dir(const char* env, const std::filesystem::path& program);

// The source tree's assets folder this program was built from (the last place looked).
std::string source_asset_dir();

// Where the documentation is (README.md and docs/): the installed copy's share/doc/fluidbed,
// found from `program` (PREFIX/bin/fluidbed -> PREFIX/share/doc/fluidbed) when it holds
// README.md; else the source tree this program was built from when it still does; else empty.
std::string find_doc_dir(const std::filesystem::path& program);
std::string doc_dir();  // find_doc_dir with the running program's path

}  // namespace fluidbed::render
