#pragma once
// fluidbed keys [SECTION] [--format text|toml|man]: every scene key with its default, unit,
// range and help, read off the field table the loader and validator use (scene/scene_keys.hpp).
// `--format toml` is a complete scene file at the defaults; `--format man` the manual page,
// which also lists the commands.
#include <string>
#include <utility>
#include <vector>

namespace fluidbed::app {

struct KeysArgs {
  std::string section;          // empty: every section
  std::string format = "text";  // text, toml, man
};

// One command of the command line as the manual page lists it (taken from the parser itself).
struct CommandDoc {
  std::string name;                                          // "run"
  std::string description;                                   // one line
  std::vector<std::pair<std::string, std::string>> options;  // "--until FLOAT", what it does
};

// Prints to standard output and returns 0; an unknown section (or one given with --format man)
// is an InputError naming it.
int keys_command(const KeysArgs& a, const std::vector<CommandDoc>& commands);

}  // namespace fluidbed::app
