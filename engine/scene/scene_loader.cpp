#include "scene/scene_loader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <toml++/toml.h>

#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "scene/toml_value.hpp"
#include <algorithm>

namespace fluidbed {
namespace {

std::string describe(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "true or false";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    default: return "a date or time";
  }
}

// Reads one section's keys from a TOML table into its struct; refuses unknown keys and wrong types.
struct Reader {
  const toml::table& table;
  std::string section;
  std::string origin;

  std::string where(std::string_view key) const {
    return origin + ": " + section + "." + std::string(key);
  }
  void type_error(std::string_view key, const toml::node& n, const std::string& expected) const {
    throw InputError(where(key) + " must be " + expected + ", not " + describe(n));
  }

  // A number (an integer reads as one); nothing for another type.
  static std::optional<double> number(const toml::node& n) {
    if (auto v = n.value_exact<double>()) return *v;
    if (auto i = n.value_exact<std::int64_t>()) return static_cast<double>(*i);
    return std::nullopt;
  }

  void operator()(std::string_view key, double& field, const FieldInfo&) const {
    const toml::node* n = table.get(key);
    if (!n) return;
    const std::optional<double> v = number(*n);
    if (!v) type_error(key, *n, "a number");
    field = *v;
    if (!std::isfinite(field)) throw InputError(where(key) + " must be a finite number");
  }
  // A number that may be left unset (it then follows another key: settings.hpp).
  void operator()(std::string_view key, std::optional<double>& field, const FieldInfo& info) const {
    if (!table.get(key)) return;
    double v = 0.0;
    (*this)(key, v, info);
    field = v;
  }
  // Points: an array of [x, y] arrays of two finite numbers each.
  void operator()(std::string_view key, std::vector<ProbePoint>& field, const FieldInfo&) const {
    const toml::node* n = table.get(key);
    if (!n) return;
    const toml::array* points = n->as_array();
    if (!points) type_error(key, *n, "an array of points [[x, y], ...]");
    field.clear();
    for (std::size_t k = 0; k < points->size(); ++k) {
      const toml::array* xy = (*points)[k].as_array();
      std::optional<double> x, y;
      if (xy && xy->size() == 2) {
        x = number(*xy->get(0));
        y = number(*xy->get(1));
      }
      if (!x || !y || !std::isfinite(*x) || !std::isfinite(*y))
        throw InputError(where(key) + ": point " + std::to_string(k + 1) +
                         " must be [x, y], two finite numbers in metres");
      field.push_back({*x, *y});
    }
  }
  void operator()(std::string_view key, int& field, const FieldInfo&) const {
    const toml::node* n = table.get(key);
    if (!n) return;
    auto v = n->value_exact<std::int64_t>();
    if (!v) type_error(key, *n, "an integer");
    if (*v < std::numeric_limits<int>::min() || *v > std::numeric_limits<int>::max())
      throw InputError(where(key) + " is out of range");
    field = static_cast<int>(*v);
  }
  void operator()(std::string_view key, std::uint64_t& field, const FieldInfo&) const {
    const toml::node* n = table.get(key);
    if (!n) return;
    auto v = n->value_exact<std::int64_t>();
    if (!v) type_error(key, *n, "an integer");
    if (*v < 0) throw InputError(where(key) + " must not be negative");
    field = static_cast<std::uint64_t>(*v);
  }
  void operator()(std::string_view key, bool& field, const FieldInfo&) const {
    const toml::node* n = table.get(key);
    if (!n) return;
    auto v = n->value_exact<bool>();
    if (!v) type_error(key, *n, "true or false");
    field = *v;
  }
  void operator()(std::string_view key, std::string& field, const FieldInfo&) const {
    const toml::node* n = table.get(key);
    if (!n) return;
    auto v = n->value_exact<std::string>();
    if (!v) type_error(key, *n, "a string");
    field = *v;
  }
  // A named choice: the name turned into its enum here, once (scene/options.hpp).
  template <class E>
    requires is_option_v<E>
  void operator()(std::string_view key, E& field, const FieldInfo&) const {
    const toml::node* n = table.get(key);
    if (!n) return;
    auto v = n->value_exact<std::string>();
    if (!v) type_error(key, *n, "a string (one of: " + option_names<E>() + ")");
    field = parse_option<E>(origin + ": " + section + "." + std::string(key), *v);
  }
};

// Collects the key names a section knows.
struct KeyLister {
  std::vector<std::string>* keys;
  template <class T>
  void operator()(std::string_view key, T&, const FieldInfo&) const {
    keys->emplace_back(key);
  }
};

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

void apply_override(toml::table& root, const std::string& text) {
  const auto eq = text.find('=');
  const auto dot = text.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq)
    throw InputError("--set " + text + ": expected section.key=value");
  const std::string section = text.substr(0, dot);
  const std::string key = text.substr(dot + 1, eq - dot - 1);
  const std::string value = text.substr(eq + 1);
  if (section.empty() || key.empty() || key.find('.') != std::string::npos)
    throw InputError("--set " + text + ": expected section.key=value");
  // The value in TOML syntax (numbers, true/false, "quoted"); a bare word is a string.
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    parsed.insert_or_assign("v", value);
  }
  if (!root.contains(section)) root.insert(section, toml::table{});
  toml::table* sec = root[section].as_table();
  if (!sec) throw InputError("--set " + text + ": " + section + " is not a section");
  sec->insert_or_assign(key, *parsed.get("v"));
}

Settings convert(const toml::table& root, const std::string& origin) {
  Settings s;
  std::vector<std::string> known_sections;
  visit_sections(s, [&](std::string_view name, auto& section) {
    known_sections.emplace_back(name);
    const toml::node* node = root.get(name);
    if (!node) return;
    const toml::table* table = node->as_table();
    if (!table) throw InputError(origin + ": " + std::string(name) + " must be a table");
    std::vector<std::string> keys;
    visit_fields(section, KeyLister{&keys});
    for (const auto& [k, v] : *table) {
      if (std::find(keys.begin(), keys.end(), k.str()) == keys.end())
        throw InputError(origin + ": unknown key " + std::string(name) + "." + std::string(k.str()) +
                         " (known: " + join(keys) + ")");
    }
    visit_fields(section, Reader{*table, std::string(name), origin});
  });
  // A [gas] section switches the gas on unless it says enabled = false.
  if (const toml::table* gas = root["gas"].as_table(); gas && !gas->contains("enabled"))
    s.gas.enabled = true;
  for (const auto& [k, v] : root) {
    if (std::find(known_sections.begin(), known_sections.end(), k.str()) == known_sections.end())
      throw InputError(origin + ": unknown section [" + std::string(k.str()) +
                       "] (known: " + join(known_sections) + ")");
  }
  return s;
}

Settings parse_root(toml::table root, const std::string& origin,
                    const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) apply_override(root, o);
  Settings s = convert(root, origin);
  validate(s);
  return s;
}

}  // namespace

Settings parse_scene(const std::string& toml_text, const std::string& origin,
                     const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw InputError(origin + ":" + std::to_string(b.line) + ":" + std::to_string(b.column) +
                     ": " + std::string(e.description()));
  }
  return parse_root(std::move(root), origin, overrides);
}

Settings load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in = open_input_file(path, "scene file");
  std::stringstream text;
  text << in.rdbuf();
  Settings s = parse_scene(text.str(), path, overrides);
  s.source_dir = std::filesystem::absolute(path).parent_path().string();
  return s;
}

namespace {

struct TomlWriter {
  std::ostringstream* out;
  template <class T>
  void operator()(std::string_view key, const T& v, const FieldInfo& info) const {
    // No probes are left out rather than written as [], so that a scene without them resolves
    // to the text it had before the key existed: the packed-bed and U_mf caches are keyed on
    // that text, and a run's resolved scene.toml stays as it was.
    if constexpr (std::is_same_v<T, std::vector<ProbePoint>>)
      if (v.empty()) return;
    // An unset number (it follows another key) is left out for the same reason.
    if constexpr (std::is_same_v<T, std::optional<double>>) {
      if (!v) return;
      *out << key << " = " << toml_value(*v);
    } else {
      *out << key << " = " << toml_value(v);
    }
    if (!info.unit.empty()) *out << "  # " << info.unit;
    *out << "\n";
  }
};

}  // namespace

std::string to_toml(const Settings& settings) {
  Settings s = settings;  // the visitors take non-const references
  std::ostringstream out;
  visit_sections(s, [&](std::string_view name, auto& section) {
    out << "[" << name << "]\n";
    visit_fields(section, TomlWriter{&out});
    out << "\n";
  });
  return out.str();
}

std::string first_difference(const std::string& now, const std::string& was) {
  std::istringstream a(now), b(was);
  std::string la, lb, section;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(a, la)),
               gb = static_cast<bool>(std::getline(b, lb));
    if (!ga && !gb) return "";
    if (!ga) la.clear();
    if (!gb) lb.clear();
    if (la != lb) {
      auto bare = [](std::string l) { return l.substr(0, l.find("  #")); };
      return section + " " + bare(la) + ", was " + bare(lb);
    }
    if (!la.empty() && la[0] == '[') section = la;
  }
}

}  // namespace fluidbed
