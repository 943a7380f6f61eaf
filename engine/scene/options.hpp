#pragma once
// The scene's named choices, resolved once: each option is an enum with one table of (name,
// value, help). The loader turns a TOML string into the enum (an unknown name is refused with the
// list of known ones), the resolved-scene writer and `fluidbed keys` turn it back, and the rest
// of the program compares enums, never strings.
#include <array>
#include <string>
#include <string_view>

#include "core/errors.hpp"

namespace fluidbed {

template <class E>
struct OptionEntry {
  std::string_view name;
  E value;
  std::string_view help;
};

// What a run measures on top of the common diagnostics.
enum class SceneKind { Bed, Drop, Packing };
// Where the particles start.
enum class Placement { Lattice, Single, State, Packed };
// How the contact displacements are found.
enum class Displacement { Incremental, Geometric };
// The contact's force law.
enum class ContactLaw { Linear, HertzMindlin };
// The particles' time integrator.
enum class Integrator { Newmark, VelocityVerlet, SymplecticEuler };
// What the bottom of the bed lets in.
enum class InletKind { Jet, Uniform, None };
// How the gas cells' void fraction is taken from the spheres.
enum class VoidFraction { Exact, Smoothed };

// The table of each option (specialised below).
template <class E>
struct Options;

template <>
struct Options<SceneKind> {
  static constexpr std::array<OptionEntry<SceneKind>, 3> entries{{
      {"bed", SceneKind::Bed, "a bed: the common diagnostics (dp, overlaps, bed height)"},
      {"drop", SceneKind::Drop, "bounce heights and restitution of a dropped particle"},
      {"packing", SceneKind::Packing, "bed height and solid fraction of a packing"},
  }};
};

template <>
struct Options<Placement> {
  static constexpr std::array<OptionEntry<Placement>, 4> entries{{
      {"lattice", Placement::Lattice,
       "the paper's random lattice start: cells of one diameter, alternate rows shifted by a "
       "radius, particles in randomly chosen cells"},
      {"single", Placement::Single, "one particle at (x, y) with (vx, vy) and spin"},
      {"state", Placement::State, "positions, velocities, spins and contact history from state_file"},
      {"packed", Placement::Packed,
       "the packing of this scene's particles (lattice start, gas at rest, packing_time of "
       "falling), made once and cached"},
  }};
};

template <>
struct Options<Displacement> {
  static constexpr std::array<OptionEntry<Displacement>, 2> entries{{
      {"incremental", Displacement::Incremental,
       "the paper's eqs 13-17: displacements accumulated from increments, the first over the "
       "backward-projected time since touching"},
      {"geometric", Displacement::Geometric, "the normal overlap R_i + R_j - L"},
  }};
};

template <>
struct Options<ContactLaw> {
  static constexpr std::array<OptionEntry<ContactLaw>, 2> entries{{
      {"linear", ContactLaw::Linear,
       "the paper's spring-dashpot (eqs 3-7): contact.stiffness and contact.damping"},
      {"hertz_mindlin", ContactLaw::HertzMindlin,
       "Hertz-Mindlin springs and dashpots from each contact's overlap (as LIGGGHTS and Lethe): "
       "contact.youngs_modulus, poisson_ratio and restitution; a thick slab only"},
  }};
};

template <>
struct Options<Integrator> {
  static constexpr std::array<OptionEntry<Integrator>, 3> entries{{
      {"newmark", Integrator::Newmark, "the paper's predictor-corrector (eqs 24-28)"},
      {"velocity_verlet", Integrator::VelocityVerlet, "velocity Verlet"},
      {"symplectic_euler", Integrator::SymplecticEuler, "symplectic Euler"},
  }};
};

template <>
struct Options<InletKind> {
  static constexpr std::array<OptionEntry<InletKind>, 3> entries{{
      {"jet", InletKind::Jet, "a plug through a slot at the centre of the bottom (the paper)"},
      {"uniform", InletKind::Uniform, "a distributor over the whole bottom"},
      {"none", InletKind::None, "a closed bottom: the gas at rest"},
  }};
};

template <>
struct Options<VoidFraction> {
  static constexpr std::array<OptionEntry<VoidFraction>, 2> entries{{
      {"exact", VoidFraction::Exact,
       "each sphere's exact share of volume in the cells it straddles (eq 22)"},
      {"smoothed", VoidFraction::Smoothed,
       "the exact shares smoothed over coupling.void_fraction_length (1 - L^2 laplacian, as "
       "Lethe's l2 smoothing length): the same total, no cell-to-cell jumps on fine grids"},
  }};
};

template <class E>
constexpr bool is_option_v = requires { Options<E>::entries; };

// The name of a value ("newmark").
template <class E>
std::string_view option_name(E value) {
  for (const auto& e : Options<E>::entries)
    if (e.value == value) return e.name;
  return "?";
}

// The same as a string, for messages and files.
template <class E>
std::string option_string(E value) {
  return std::string(option_name(value));
}

// The known names, "a, b, c".
template <class E>
std::string option_names() {
  std::string list;
  for (const auto& e : Options<E>::entries) {
    if (!list.empty()) list += ", ";
    list += e.name;
  }
  return list;
}

// The value of a name; an unknown one is an InputError naming `key` and the known names.
template <class E>
E parse_option(std::string_view key, std::string_view text) {
  for (const auto& e : Options<E>::entries)
    if (e.name == text) return e.value;
  throw InputError(std::string(key) + " is \"" + std::string(text) + "\"; expected one of: " +
                   option_names<E>());
}

}  // namespace fluidbed
