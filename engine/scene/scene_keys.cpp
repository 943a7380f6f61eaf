#include "scene/scene_keys.hpp"

#include <charconv>

#include "scene/settings.hpp"
#include "scene/toml_value.hpp"

namespace fluidbed {
namespace {

std::string type_of(double) { return "number"; }
std::string type_of(const std::optional<double>&) { return "number"; }
std::string type_of(int) { return "integer"; }
std::string type_of(std::uint64_t) { return "integer"; }
std::string type_of(bool) { return "true or false"; }
std::string type_of(const std::string&) { return "text"; }
std::string type_of(const std::vector<ProbePoint>&) { return "list of points"; }
template <class E>
  requires is_option_v<E>
std::string type_of(E) {
  return "choice";
}

// A default as a person writes it: the shortest text that reads back as the same double
// (0.15, not the resolved-scene writer's 0.14999999999999999, whose text the packed-bed cache
// hashes and so stays as it is), with ".0" where TOML would otherwise read an integer.
std::string default_text(double v) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  std::string t(buf, end);
  if (t.find_first_of(".eEn") == std::string::npos) t += ".0";
  return t;
}
// Unset by default: it follows another key (its help says which).
std::string default_text(const std::optional<double>& v) {
  return v ? default_text(*v) : std::string("unset");
}
template <class T>
std::string default_text(const T& v) {
  return toml_value(v);
}

// Reads one section's fields off the table into SceneKeys.
struct KeyCollector {
  std::string section;
  std::vector<SceneKey>* keys;

  template <class T>
  void operator()(std::string_view name, const T& v, const FieldInfo& info) const {
    SceneKey k;
    k.section = section;
    k.name = std::string(name);
    k.type = type_of(v);
    k.default_value = default_text(v);
    if constexpr (std::is_same_v<T, std::optional<double>>) k.unset = !v;
    k.unit = std::string(info.unit);
    k.help = std::string(info.help);
    if constexpr (is_option_v<T>) {
      k.range = option_names<T>();
      for (const auto& e : Options<T>::entries) k.choices.emplace_back(e.name, e.help);
    } else if constexpr (std::is_same_v<T, bool>) {
      k.range = "true, false";
    } else if constexpr (std::is_same_v<T, std::string>) {
      k.range = "any text";
    } else if constexpr (std::is_same_v<T, std::vector<ProbePoint>>) {
      k.range = "[x, y] in the gas domain";
    } else {
      k.range = info.range.text();
    }
    keys->push_back(std::move(k));
  }
};

}  // namespace

std::vector<SceneKey> scene_keys() {
  Settings defaults;
  std::vector<SceneKey> keys;
  visit_sections(defaults, [&keys](std::string_view name, auto& section) {
    visit_fields(section, KeyCollector{std::string(name), &keys});
  });
  return keys;
}

std::vector<std::string> scene_sections() {
  Settings defaults;
  std::vector<std::string> names;
  visit_sections(defaults, [&names](std::string_view name, auto&) { names.emplace_back(name); });
  return names;
}

}  // namespace fluidbed
