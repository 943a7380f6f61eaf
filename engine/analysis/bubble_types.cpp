// The plain data of the bubble analysis: the jet slots, the settings' defaults and checks, and
// the names of events and regimes (analysis/bubble_types.hpp).
#include "analysis/bubble_types.hpp"

#include <cmath>
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

const char* to_string(BubbleEvent e) {
  switch (e) {
    case BubbleEvent::none:
      return "";
    case BubbleEvent::formed:
      return "formed";
    case BubbleEvent::coalesced:
      return "coalesced";
    case BubbleEvent::split:
      return "split";
    case BubbleEvent::erupted:
      return "erupted";
    case BubbleEvent::vanished:
      return "vanished";
  }
  return "";
}

const char* to_string(Regime r) {
  switch (r) {
    case Regime::fixed:
      return "fixed";
    case Regime::bubbling:
      return "bubbling";
    case Regime::slugging:
      return "slugging";
    case Regime::spouting:
      return "spouting";
  }
  return "";
}

}  // namespace fluidbed
