#pragma once
// The points of studies 1 and 2 (app/studies/accuracy.cpp): one variant (integrator, contact
// form) at one step, measured by the drop, restitution and packing tests, and kept in the
// study's point store. The settled packing the packing tests start from.
#include <string>
#include <vector>

#include "scene/settings.hpp"
#include "studies/common.hpp"

namespace fluidbed::app::study::accuracy {

// Energy gain per particle (in m g D) that marks a step unstable. A stable scheme's energy error
// in a packing at rest is of the order of the elastic energy per contact, below 1e-2 m g D here
// (a bottom contact under 65 layers stores about 2e-8 J; m g D = 3.5e-6 J); an unstable one grows
// geometrically through any threshold within a few hundred steps. 0.1 m g D is every particle
// lifted by a tenth of its diameter: the bed would visibly boil.
constexpr double kGrowthLimit = 0.1;
constexpr double kDropSpeed = 1.0;  // m/s at impact

struct Variant {
  Integrator integrator = Integrator::Newmark;
  Displacement displacement = Displacement::Incremental;
  std::string label() const {
    return (integrator == Integrator::Newmark ? std::string("predictor-corrector (newmark)")
                                              : option_string(integrator)) +
           ", " + option_string(displacement);
  }
  std::string short_label(bool by_contact) const {
    return by_contact ? option_string(displacement) : option_string(integrator);
  }
};

struct Config {
  std::vector<Variant> variants;
  bool by_contact = false;          // study 2: the variants differ in contact form
  std::vector<double> multipliers;  // of t_c / 9
  int phases = 8;                   // restitution: contact phases averaged
  int drop_phases = 4;              // drop test: contact phases averaged
  int rest_count = 2400;
  double rest_width = 0.15, rest_height = 0.9, rest_fill = 0.3, settle_time = 0.5;
  double energy_time = 0.1;  // s
};

// One variant at one step: what the three tests measured.
struct StepResult {
  double mult = 0.0, dt = 0.0;
  bool drop_ok = false, rest_ok = false, pack_ok = false;
  std::string drop_error, rest_error, pack_error, pack_kind;
  double drop_ratio = NAN, drop_err = NAN;
  double e_mean = NAN, e_err = NAN, e_spread = NAN;
  double growth = NAN, drift = NAN, cost = NAN, cost_wall = NAN, psteps = NAN;
  bool stable() const { return pack_ok && drop_ok && rest_ok; }
  bool failed() const { return !stable(); }
  std::string error() const {
    if (!pack_ok) return pack_error;
    if (!drop_ok) return drop_error;
    if (!rest_ok) return rest_error;
    return "";
  }
  std::string kind() const {
    if (!pack_ok) return pack_kind;
    const std::string e = error();
    return e.empty() ? "" : (e.find("bounces") != std::string::npos ? "energy" : failure_kind(e));
  }
};

// The settled packing every packing test starts from: frictionless spheres on the random lattice,
// damped (eta = 0.5 kg/s) with the paper's scheme at half the paper's step until at rest; kept
// as DIR/rest.state.
struct RestState {
  std::string path;
  Settings settings;
  double kinetic_per_particle = 0.0;  // in m g D, when the undamped tests start
  double solid_fraction = 0.0, bed_height = 0.0;
};
RestState make_rest_state(const Options& o, const Config& c);

// The three tests of variant V at MULT x t_c / 9, as a stored point: the study's folder holds one
// study at one size (study.json), so the variant, the multiplier and the packing it starts from
// define it.
StepResult stored_step(const Options& o, const Config& c, const RestState& rest, const Variant& v,
                       double mult);

}  // namespace fluidbed::app::study::accuracy
