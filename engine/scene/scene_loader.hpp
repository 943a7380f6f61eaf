#pragma once
// Reading a scene: TOML file -> --set overrides -> Settings -> one validation pass. Every problem
// is an InputError whose message names the file, section and key.
#include <string>
#include <vector>

#include "scene/settings.hpp"

namespace fluidbed {

// Parse `path`, apply overrides of the form "section.key=value" (value in TOML syntax; a bare word
// is taken as a string), convert and validate. Unknown sections and keys are refused.
Settings load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// The same from TOML text (tests, built-in scenes). `origin` names the text in messages.
Settings parse_scene(const std::string& toml_text, const std::string& origin,
                     const std::vector<std::string>& overrides = {});

// Checks every value against physics and geometry; throws InputError naming the key.
void validate(const Settings& s);

// The fully resolved scene as TOML (every key, defaults included), for the run's output folder.
std::string to_toml(const Settings& s);
// The first line where two scenes of to_toml differ, as "[section] key = value, was key = value"
// ("" when they are the same): why a resume refuses a changed scene.
std::string first_difference(const std::string& now, const std::string& was);

}  // namespace fluidbed
