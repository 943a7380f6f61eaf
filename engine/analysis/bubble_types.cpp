// The plain data of the bubble analysis: the jet slots, the settings' defaults and checks, and
// the names of events and regimes (analysis/bubble_types.hpp).
#include "analysis/bubble_types.hpp"

#include <cmath>
#include <cstddef>
#include <iterator>
#include <sstream>
#include <string>

#include "analysis/void_fraction.hpp"
#include "core/errors.hpp"

namespace fluidbed {

namespace {

[[noreturn]] void bad_setting(const char* key, const std::string& why, double v, const char* unit) {
  std::ostringstream os;
  os << "bubbles." << key << " " << why << " (got " << v << unit << ")";
  throw InputError(os.str());
}

}  // namespace

std::vector<JetSlot> jet_slots(double domain_width, int jets, double jet_width) {
  std::vector<JetSlot> slots;
  for (int k = 0; k < jets; ++k) slots.push_back({(k + 0.5) * domain_width / jets, jet_width});
  return slots;
}

BubbleSettings default_bubble_settings(double particle_diameter) {
  BubbleSettings s;
  s.min_diameter = 2.0 * particle_diameter;
  s.cell_size = 0.5 * particle_diameter;
  s.window = 2.5 * particle_diameter;
  s.expanded_rise = particle_diameter;
  s.expanded_speed = particle_diameter / 1.0;  // a diameter a second
  return s;
}

void validate(const BubbleSettings& s, const BedGeometry& g) {
  if (!(s.threshold > 0.0 && s.threshold < 1.0))
    bad_setting("threshold", "must be in (0, 1)", s.threshold, "");
  if (!(s.min_diameter >= 0.0) || !std::isfinite(s.min_diameter))
    bad_setting("min_diameter", "must be a length >= 0", s.min_diameter, " m");
  if (!(s.interval > 0.0) || !std::isfinite(s.interval))
    bad_setting("interval", "must be positive", s.interval, " s");
  if (!(s.slug_fraction > 0.0 && s.slug_fraction <= 1.0))
    bad_setting("slug_fraction", "must be in (0, 1]", s.slug_fraction, "");
  if (!(s.slugging_min_fraction > 0.0 && s.slugging_min_fraction <= 1.0))
    bad_setting("slugging_min_fraction", "must be in (0, 1]", s.slugging_min_fraction, "");
  if (!(s.spouting_min_fraction > 0.0 && s.spouting_min_fraction <= 1.0))
    bad_setting("spouting_min_fraction", "must be in (0, 1]", s.spouting_min_fraction, "");
  if (!(s.bed_min_fraction >= 0.0 && s.bed_min_fraction < 1.0))
    bad_setting("bed_min_fraction", "must be in [0, 1)", s.bed_min_fraction, "");
  if (s.min_track_frames < 1)
    bad_setting("min_track_frames", "must be at least 1", s.min_track_frames, "");
  if (!(s.eruption_gap >= 0.0) || !std::isfinite(s.eruption_gap))
    bad_setting("eruption_gap", "must be a time >= 0", s.eruption_gap, " s");
  make_void_fraction_field(
      make_fine_grid(g.width, g.height, g.thickness, s.cell_size, g.particle_diameter), s.window);
}

// The names in the enums' order (bubble_types.hpp).
const char* to_string(BubbleEvent e) {
  static constexpr const char* kNames[] = {"", "formed", "coalesced", "split", "erupted", "vanished"};
  const auto k = static_cast<std::size_t>(e);
  return k < std::size(kNames) ? kNames[k] : "";
}

const char* to_string(Regime r) {
  static constexpr const char* kNames[] = {"fixed", "bubbling", "slugging", "spouting",
                                           "expanded"};
  const auto k = static_cast<std::size_t>(r);
  return k < std::size(kNames) ? kNames[k] : "";
}

}  // namespace fluidbed
