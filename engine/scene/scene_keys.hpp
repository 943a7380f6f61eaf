#pragma once
// Every scene key as `fluidbed keys` and the man page show it, read off the field table
// (scene/settings.hpp: visit_fields), so the listing is the loader's own.
#include <string>
#include <utility>
#include <vector>

namespace fluidbed {

struct SceneKey {
  std::string section;        // "contact"
  std::string name;           // "stiffness"
  std::string type;           // "number", "integer", "true or false", "text", "choice"
  std::string default_value;  // the default in TOML syntax: 50000.0, "lattice", true
  std::string unit;           // SI; empty for none
  std::string range;          // "> 0", "(0, 1]"; a choice: its names; text: "any text"
  std::string help;           // one line
  std::vector<std::pair<std::string, std::string>> choices;  // a choice: each name and its help
  bool unset = false;  // no default of its own: it follows the key its help names
};

// Every key of every section, in file order.
std::vector<SceneKey> scene_keys();

// The section names, in file order.
std::vector<std::string> scene_sections();

}  // namespace fluidbed
