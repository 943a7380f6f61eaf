#pragma once
// What a particle's colour shows, and the names it goes by, in one table: the command line's
// --colour, the error messages and `to_string` use the modes' own names; the viewer (the panel's
// buttons, the `c` key, scripts' `colour MODE`) has its own words for some ("mixing" for the
// initial-height bands) and leaves out the one colour. No GL: the view scripts' parser
// (app/view) checks its words here.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.hpp"

namespace fluidbed::render {

enum class ColourBy {
  speed,    // |v| (m/s)
  force,    // |F| total force: contacts, gravity, gas (N) - Fig. 14c
  torque,   // |T| (N m) - Fig. 14d
  overlap,  // largest overlap ratio of the particle's contacts (-) - Fig. 15's measure
  height,   // initial height, in bands, to watch mixing (m)
  depth,    // z across the slab from the front wall (m): a thick bed's layers
  fixed,    // one colour
};

// Where a name is used: `mode` is the mode's own name (one per mode: --colour, to_string,
// messages), `viewer` one of the viewer's words (in the table's order: the panel's buttons and
// the `c` key's cycle), `both` the two.
enum class ColourNameUse { both, mode, viewer };

struct ColourByName {
  std::string_view name;
  ColourBy value;
  ColourNameUse use;
};

inline constexpr std::array<ColourByName, 8> kColourByNames{{
    {"speed", ColourBy::speed, ColourNameUse::both},
    {"force", ColourBy::force, ColourNameUse::both},
    {"torque", ColourBy::torque, ColourNameUse::both},
    {"overlap", ColourBy::overlap, ColourNameUse::both},
    {"height", ColourBy::height, ColourNameUse::mode},
    {"mixing", ColourBy::height, ColourNameUse::viewer},  // what the bands show
    {"depth", ColourBy::depth, ColourNameUse::both},
    {"fixed", ColourBy::fixed, ColourNameUse::mode},
}};

constexpr bool is_mode_name(const ColourByName& n) {
  return n.use != ColourNameUse::viewer;
}
constexpr bool is_viewer_name(const ColourByName& n) {
  return n.use != ColourNameUse::mode;
}

// The modes' own names: "speed", "force", ..., "fixed" (the enum's order).
inline std::vector<std::string> colour_by_names() {
  std::vector<std::string> out;
  for (const ColourByName& n : kColourByNames)
    if (is_mode_name(n)) out.emplace_back(n.name);
  return out;
}

// The viewer's words: "speed", "force", "torque", "overlap", "mixing", "depth".
inline std::vector<std::string> viewer_colour_names() {
  std::vector<std::string> out;
  for (const ColourByName& n : kColourByNames)
    if (is_viewer_name(n)) out.emplace_back(n.name);
  return out;
}

// "a, b, c".
inline std::string joined_colour_names(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

inline std::string to_string(ColourBy c) {
  for (const ColourByName& n : kColourByNames)
    if (n.value == c && is_mode_name(n)) return std::string(n.name);
  return "?";
}

// Any name of the table, the viewer's words included ("mixing": height).
inline std::optional<ColourBy> find_colour_by(std::string_view name) {
  for (const ColourByName& n : kColourByNames)
    if (n.name == name) return n.value;
  return std::nullopt;
}

// A mode's own name (the command line); InputError listing them for any other.
inline ColourBy parse_colour_by(const std::string& name) {
  for (const ColourByName& n : kColourByNames)
    if (is_mode_name(n) && n.name == name) return n.value;
  throw InputError("unknown colour mode '" + name + "' (known: " +
                   joined_colour_names(colour_by_names()) + ")");
}

// One of the viewer's words; InputError listing them for any other.
inline ColourBy parse_viewer_colour(const std::string& name) {
  for (const ColourByName& n : kColourByNames)
    if (is_viewer_name(n) && n.name == name) return n.value;
  throw InputError("unknown colour mode '" + name + "' (known: " +
                   joined_colour_names(viewer_colour_names()) + ")");
}

}  // namespace fluidbed::render
