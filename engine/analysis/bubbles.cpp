#include "analysis/bubbles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "core/binary_io.hpp"
#include "core/errors.hpp"

namespace fluidbed {

namespace {

[[noreturn]] void bad_setting(const char* key, const std::string& why, double v, const char* unit) {
  std::ostringstream os;
  os << "bubbles." << key << " " << why << " (got " << v << unit << ")";
  throw InputError(os.str());
}

double equivalent_diameter(double area) {
  return std::sqrt(4.0 * area / std::numbers::pi);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Settings

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

// ---------------------------------------------------------------------------------------------
// Detection

BubbleDetector::BubbleDetector(const BubbleSettings& s, const BedGeometry& g) : s_(s), g_(g) {}

void BubbleDetector::detect(const VoidFractionField& field, BubbleFrame& frame) {
  const FineGrid& G = field.grid;
  const int nx = G.nx, ny = G.ny;
  const auto cells = static_cast<std::size_t>(G.cells());
  const std::vector<double>& eps = field.eps_window;
  const double thr = s_.threshold;
  // Rows above the highest sphere hold no solid: all freeboard. The labelling stops at the first
  // of them, which the freeboard region then reaches (or at the top of the domain).
  const int rows = std::min(ny, field.top_row + 1);

  if (static_cast<int>(jet_column_.size()) != nx) {
    jet_column_.assign(static_cast<std::size_t>(nx), 0);
    for (int i = 0; i < nx; ++i)
      for (const JetSlot& slot : g_.jets)
        if (i * G.dx < slot.centre + 0.5 * slot.width &&
            (i + 1) * G.dx > slot.centre - 0.5 * slot.width)
          jet_column_[static_cast<std::size_t>(i)] = 1;
  }

  comp_.assign(cells, -1);
  regions_.clear();
  const int active = rows * nx;
  void_.resize(cells);
  for (int c = 0; c < active; ++c)
    void_[static_cast<std::size_t>(c)] = eps[static_cast<std::size_t>(c)] > thr;
  // Connected regions of one kind (void with 4 neighbours, dense with 8), numbered in the order
  // of their first cell in row-major order (deterministic).
  const auto fill = [&](int i0, int j0, bool void_kind) {
    const int k = static_cast<int>(regions_.size());
    const std::uint8_t kind = void_kind ? 1 : 0;
    Region r;
    r.void_cells = void_kind;
    r.i_min = nx;
    r.j_min = ny;
    r.i_max = -1;
    r.j_max = -1;
    const auto visit = [&](int i, int j) {
      const auto n = static_cast<std::size_t>(i + nx * j);
      if (comp_[n] >= 0 || void_[n] != kind) return;
      comp_[n] = k;
      cell_stack_.push_back({i, j});
    };
    comp_[static_cast<std::size_t>(i0 + nx * j0)] = k;
    cell_stack_.push_back({i0, j0});
    while (!cell_stack_.empty()) {
      const auto [i, j] = cell_stack_.back();
      cell_stack_.pop_back();
      ++r.cells;
      r.sum_i += i;
      r.sum_j += j;
      r.i_min = std::min(r.i_min, i);
      r.i_max = std::max(r.i_max, i);
      r.j_min = std::min(r.j_min, j);
      r.j_max = std::max(r.j_max, j);
      if (j == rows - 1) r.touches_top = true;
      if (i == 0 || i == nx - 1) r.touches_wall = true;
      if (j == 0 && jet_column_[static_cast<std::size_t>(i)]) r.touches_jet = true;
      const bool left = i > 0, right = i + 1 < nx, down = j > 0, up = j + 1 < rows;
      if (left) visit(i - 1, j);
      if (right) visit(i + 1, j);
      if (down) visit(i, j - 1);
      if (up) visit(i, j + 1);
      if (!void_kind) {  // dense: the diagonal neighbours too
        if (left && down) visit(i - 1, j - 1);
        if (right && down) visit(i + 1, j - 1);
        if (left && up) visit(i - 1, j + 1);
        if (right && up) visit(i + 1, j + 1);
      }
    }
    regions_.push_back(r);
  };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < nx; ++i) {
      const auto c = static_cast<std::size_t>(i + nx * j);
      if (comp_[c] < 0) fill(i, j, void_[c] != 0);
    }

  // The bed: the dense regions holding at least bed_min_fraction of the dense cells. Its surface
  // per column: the top of its highest cell there.
  long dense_cells = 0;
  for (const Region& r : regions_)
    if (!r.void_cells) dense_cells += r.cells;
  const double bed_min = s_.bed_min_fraction * static_cast<double>(dense_cells);
  frame.surface.assign(static_cast<std::size_t>(nx), 0.0);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < nx; ++i) {
      const Region& r =
          regions_[static_cast<std::size_t>(comp_[static_cast<std::size_t>(i + nx * j)])];
      if (!r.void_cells && static_cast<double>(r.cells) >= bed_min)
        frame.surface[static_cast<std::size_t>(i)] = (j + 1) * G.dy;
    }

  // Classify the void regions; the label of a void region: its index among frame.regions, or
  // kCellFreeboard / kCellSmallVoid.
  frame.regions.clear();
  frame.spout = false;
  std::vector<int>& label = frame.label;
  label.assign(cells, kCellFreeboard);  // the rows above `rows` stay freeboard
  // class_of_[k]: the label of component k.
  class_of_.assign(regions_.size(), kCellDense);
  const double cell_area = G.cell_area();
  for (std::size_t k = 0; k < regions_.size(); ++k) {
    const Region& r = regions_[k];
    if (!r.void_cells) continue;
    if (r.touches_top) {
      class_of_[k] = kCellFreeboard;
      if (r.touches_jet) frame.spout = true;
      continue;
    }
    const double area = r.cells * cell_area;
    const double d_eq = equivalent_diameter(area);
    if (d_eq < s_.min_diameter) {
      class_of_[k] = kCellSmallVoid;
      continue;
    }
    Bubble b;
    b.cells = r.cells;
    b.x = (r.sum_i / r.cells + 0.5) * G.dx;
    b.y = (r.sum_j / r.cells + 0.5) * G.dy;
    if (!r.touches_jet) {
      const int ic = std::clamp(static_cast<int>(b.x / G.dx), 0, nx - 1);
      if (b.y > frame.surface[static_cast<std::size_t>(ic)]) {  // a pocket above the bed
        class_of_[k] = kCellFreeboard;
        continue;
      }
    }
    b.area = area;
    b.d_eq = d_eq;
    b.i_min = r.i_min;
    b.i_max = r.i_max;
    b.j_min = r.j_min;
    b.j_max = r.j_max;
    b.width = (r.i_max - r.i_min + 1) * G.dx;
    b.height = (r.j_max - r.j_min + 1) * G.dy;
    b.aspect_ratio = b.height / b.width;
    b.touches_wall = r.touches_wall;
    b.touches_jet = r.touches_jet;
    b.slug = !r.touches_jet && b.width > s_.slug_fraction * g_.width;
    b.d_eq_max = d_eq;
    b.roof = frame.surface[static_cast<std::size_t>(
                 std::clamp(static_cast<int>(b.x / G.dx), 0, nx - 1))] -
             (r.j_max + 1) * G.dy;
    class_of_[k] = static_cast<int>(frame.regions.size());
    frame.regions.push_back(b);
  }
  for (int c = 0; c < active; ++c) {
    const auto uc = static_cast<std::size_t>(c);
    label[uc] = class_of_[static_cast<std::size_t>(comp_[uc])];
  }
  class_of_.clear();
  for (std::size_t k = 0; k < frame.regions.size(); ++k)
    weighted_centroid(field, label, static_cast<int>(k), frame.regions[k]);
}

// The centroid of the region's void, sum w (x, y) / sum w with w = eps_window - floor and
// floor = threshold - kCentroidBand (0.7), over the region and the dense cells bordering it (8
// neighbours). The plain centroid of the cells above the threshold jumps by a fraction of a
// cell whenever a boundary cell crosses it: on holes of 16-40 mm moved by 3.5-7 mm per frame
// through a packed layer (up, across, diagonally; 9 frames each) its velocity erred by up to
// 13 % (rms 4 %). The weight is continuous across the threshold and vanishes a little outside it
// (the window field climbs from the bed's 0.4 to 1 over about one window), so this centroid moves
// continuously with the particles: the same cases err by at most 1.4 % (rms 0.6 %). A floor of
// 0.5 reached into the bed's own fluctuations: 9 %.
void BubbleDetector::weighted_centroid(const VoidFractionField& field,
                                       const std::vector<int>& label, int k, Bubble& b) const {
  const FineGrid& G = field.grid;
  const double floor = std::max(0.0, s_.threshold - kCentroidBand);
  const auto at = [&](int i, int j) { return label[static_cast<std::size_t>(G.index(i, j))]; };
  double sw = 0.0, sx = 0.0, sy = 0.0;
  for (int j = std::max(0, b.j_min - 1); j <= std::min(G.ny - 1, b.j_max + 1); ++j) {
    for (int i = std::max(0, b.i_min - 1); i <= std::min(G.nx - 1, b.i_max + 1); ++i) {
      const int l = at(i, j);
      if (l != k) {
        if (l != kCellDense && l != kCellSmallVoid) continue;
        bool borders = false;
        for (int dj = -1; dj <= 1 && !borders; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ii = i + di, jj = j + dj;
            if (ii >= 0 && ii < G.nx && jj >= 0 && jj < G.ny && at(ii, jj) == k) {
              borders = true;
              break;
            }
          }
        if (!borders) continue;
      }
      const double w =
          std::max(0.0, field.eps_window[static_cast<std::size_t>(G.index(i, j))] - floor);
      sw += w;
      sx += w * G.x_centre(i);
      sy += w * G.y_centre(j);
    }
  }
  if (sw > 0.0) {
    b.x = sx / sw;
    b.y = sy / sw;
  }
}

// ---------------------------------------------------------------------------------------------
// Tracking

BubbleTracker::BubbleTracker(const BubbleSettings& s, const FineGrid& grid) : s_(s), grid_(grid) {}

void BubbleTracker::track(BubbleFrame& frame) {
  frame.ended.clear();
  std::vector<Bubble>& cur = frame.regions;
  if (!has_prev_) {
    for (Bubble& b : cur) {
      b.id = next_id_++;
      b.event = b.touches_jet ? BubbleEvent::none : BubbleEvent::formed;
    }
    prev_ = frame;
    has_prev_ = true;
    return;
  }
  const double dt = frame.t - prev_.t;
  if (!(dt > 0.0)) throw std::invalid_argument("BubbleTracker::track: time must increase");
  const std::vector<Bubble>& old = prev_.regions;
  const std::size_t P = old.size(), C = cur.size();
  const int nx = grid_.nx, ny = grid_.ny;

  // Overlap of each previous region, shifted by its predicted displacement, with the current
  // regions and with the freeboard.
  overlap_.assign(P * C, 0);
  std::vector<int> freeboard(P, 0);
  for (std::size_t p = 0; p < P; ++p) {
    const Bubble& b = old[p];
    const int si = b.has_velocity ? static_cast<int>(std::lround(b.vx * dt / grid_.dx)) : 0;
    const int sj = b.has_velocity ? static_cast<int>(std::lround(b.vy * dt / grid_.dy)) : 0;
    for (int j = b.j_min; j <= b.j_max; ++j) {
      const int jj = j + sj;
      if (jj < 0 || jj >= ny) continue;
      for (int i = b.i_min; i <= b.i_max; ++i) {
        const int ii = i + si;
        if (ii < 0 || ii >= nx) continue;
        if (prev_.label[static_cast<std::size_t>(grid_.index(i, j))] != static_cast<int>(p))
          continue;
        const int l = frame.label[static_cast<std::size_t>(grid_.index(ii, jj))];
        if (l >= 0)
          ++overlap_[p * C + static_cast<std::size_t>(l)];
        else if (l == kCellFreeboard)
          ++freeboard[p];
      }
    }
  }
  const auto ov = [&](std::size_t p, std::size_t c) { return overlap_[p * C + c]; };

  // Main child of each previous region (a jet cavity prefers a jet child, so that the cavity
  // keeps its id and the detached part is the new bubble), main parent of each current one.
  std::vector<int> main_child(P, -1), children(P, 0), main_parent(C, -1), parents(C, 0);
  for (std::size_t p = 0; p < P; ++p) {
    int best = 0;
    bool best_jet = false;
    for (std::size_t c = 0; c < C; ++c) {
      const int o = ov(p, c);
      if (o == 0) continue;
      ++children[p];
      const bool jet = old[p].touches_jet && cur[c].touches_jet;
      if ((jet && !best_jet) || (jet == best_jet && o > best)) {
        best = o;
        best_jet = jet;
        main_child[p] = static_cast<int>(c);
      }
    }
  }
  for (std::size_t c = 0; c < C; ++c) {
    int best = 0;
    for (std::size_t p = 0; p < P; ++p) {
      const int o = ov(p, c);
      if (o == 0) continue;
      ++parents[c];
      if (o > best) {
        best = o;
        main_parent[c] = static_cast<int>(p);
      }
    }
  }

  const auto set_velocity = [&](Bubble& b, const Bubble& from) {
    b.vx = (b.x - from.x) / dt;
    b.vy = (b.y - from.y) / dt;
    b.has_velocity = true;
  };
  for (std::size_t c = 0; c < C; ++c) {
    Bubble& b = cur[c];
    b.event = BubbleEvent::none;
    b.has_velocity = false;
    b.vx = b.vy = 0.0;
    b.from_jet = false;
    b.merged_id = -1;
    if (parents[c] == 0) continue;  // matched by distance below, or new
    const auto p = static_cast<std::size_t>(main_parent[c]);
    const Bubble& a = old[p];
    const bool inherit = main_child[p] == static_cast<int>(c);
    b.id = inherit ? a.id : next_id_++;
    if (!b.touches_jet) {
      if (a.touches_jet) {
        b.event = BubbleEvent::formed;
        b.from_jet = true;
      } else if (parents[c] > 1) {
        b.event = BubbleEvent::coalesced;
        int best = 0;  // the largest parent besides the main one
        for (std::size_t q = 0; q < P; ++q)
          if (q != p && ov(q, c) > best && !old[q].touches_jet) {
            best = ov(q, c);
            b.merged_id = old[q].id;
          }
      } else if (!inherit) {
        b.event = BubbleEvent::split;
      }
    }
    if (inherit && parents[c] == 1 && children[p] == 1 && a.touches_jet == b.touches_jet)
      set_velocity(b, a);
    // The largest size of the id: carried on by the id's continuation and by a coalescence;
    // a part split off, or a bubble just detached from the jet, starts from its own.
    if ((inherit || parents[c] > 1) && !b.from_jet)
      for (std::size_t q = 0; q < P; ++q)
        if (ov(q, c) > 0 && !old[q].touches_jet) b.d_eq_max = std::max(b.d_eq_max, old[q].d_eq_max);
  }
  // A previous bubble without a child erupted when it reached the freeboard or lay closer to the
  // surface than its largest size (see the top of bubbles.hpp).
  const auto erupted = [&](std::size_t p) {
    return freeboard[p] > 0 || old[p].roof < old[p].d_eq_max;
  };

  // Regions left without overlap: a previous bubble that did not reach the freeboard and a new
  // bubble near its predicted centroid (closer than the sum of their D_e) are the same bubble:
  // it moved further than its size.
  struct Pair {
    double distance;
    std::size_t p, c;
  };
  std::vector<Pair> pairs;
  for (std::size_t p = 0; p < P; ++p) {
    const Bubble& a = old[p];
    if (children[p] > 0 || a.touches_jet || erupted(p)) continue;
    const double px = a.x + (a.has_velocity ? a.vx * dt : 0.0);
    const double py = a.y + (a.has_velocity ? a.vy * dt : 0.0);
    for (std::size_t c = 0; c < C; ++c) {
      const Bubble& b = cur[c];
      if (parents[c] > 0 || b.touches_jet) continue;
      const double d = std::hypot(b.x - px, b.y - py);
      if (d < a.d_eq + b.d_eq) pairs.push_back({d, p, c});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& u, const Pair& v) {
    return std::tie(u.distance, u.p, u.c) < std::tie(v.distance, v.p, v.c);
  });
  std::vector<char> p_done(P, 0), c_done(C, 0);
  for (const Pair& q : pairs) {
    if (p_done[q.p] || c_done[q.c]) continue;
    p_done[q.p] = c_done[q.c] = 1;
    cur[q.c].id = old[q.p].id;
    cur[q.c].d_eq_max = std::max(cur[q.c].d_eq_max, old[q.p].d_eq_max);
    set_velocity(cur[q.c], old[q.p]);
  }
  for (std::size_t c = 0; c < C; ++c) {
    if (parents[c] > 0 || c_done[c]) continue;
    cur[c].id = next_id_++;
    if (!cur[c].touches_jet) cur[c].event = BubbleEvent::formed;
  }
  for (std::size_t p = 0; p < P; ++p) {
    if (children[p] > 0 || p_done[p] || old[p].touches_jet) continue;
    Bubble e = old[p];
    e.event = erupted(p) ? BubbleEvent::erupted : BubbleEvent::vanished;
    frame.ended.push_back(e);
  }
  prev_ = frame;
}

namespace {

void put_bubble(std::ostream& out, const Bubble& b) {
  put(out, b.id);
  put(out, b.merged_id);
  for (double v : {b.x, b.y, b.area, b.d_eq, b.width, b.height, b.aspect_ratio, b.vx, b.vy,
                   b.d_eq_max, b.roof})
    put(out, v);
  for (int v : {b.cells, b.i_min, b.i_max, b.j_min, b.j_max}) put(out, v);
  for (bool v : {b.touches_wall, b.touches_jet, b.slug, b.has_velocity, b.from_jet})
    put(out, static_cast<std::uint8_t>(v));
  put(out, static_cast<std::uint8_t>(b.event));
}

Bubble get_bubble(BinarySource& in) {
  Bubble b;
  b.id = in.get<int>();
  b.merged_id = in.get<int>();
  for (double* v : {&b.x, &b.y, &b.area, &b.d_eq, &b.width, &b.height, &b.aspect_ratio, &b.vx,
                    &b.vy, &b.d_eq_max, &b.roof})
    *v = in.get<double>();
  for (int* v : {&b.cells, &b.i_min, &b.i_max, &b.j_min, &b.j_max}) *v = in.get<int>();
  for (bool* v : {&b.touches_wall, &b.touches_jet, &b.slug, &b.has_velocity, &b.from_jet})
    *v = in.get<std::uint8_t>() != 0;
  const auto e = in.get<std::uint8_t>();
  if (e > static_cast<std::uint8_t>(BubbleEvent::vanished)) in.fail("inconsistent (bubble event)");
  b.event = static_cast<BubbleEvent>(e);
  return b;
}

constexpr std::uint32_t kTrackerMagic = 0x42554231;   // "BUB1"
constexpr std::uint32_t kAnalysisMagic = 0x42554841;  // "BUHA"

}  // namespace

void BubbleTracker::save(std::ostream& out) const {
  put(out, kTrackerMagic);
  put(out, static_cast<std::uint8_t>(has_prev_));
  put(out, next_id_);
  put(out, prev_.t);
  put(out, static_cast<std::uint8_t>(prev_.spout));
  put(out, static_cast<std::uint64_t>(prev_.regions.size()));
  for (const Bubble& b : prev_.regions) put_bubble(out, b);
  put_vec(out, prev_.label);
  put_vec(out, prev_.surface);
}

void BubbleTracker::load(std::istream& in_stream, const std::string& origin) {
  BinarySource in(in_stream, origin);
  if (in.get<std::uint32_t>() != kTrackerMagic) in.fail("inconsistent (bubble tracker)");
  has_prev_ = in.get<std::uint8_t>() != 0;
  next_id_ = in.get<int>();
  prev_ = BubbleFrame{};
  prev_.t = in.get<double>();
  prev_.spout = in.get<std::uint8_t>() != 0;
  const auto n = in.get<std::uint64_t>();
  if (n > static_cast<std::uint64_t>(grid_.cells())) in.fail("inconsistent (bubble count)");
  for (std::uint64_t k = 0; k < n; ++k) prev_.regions.push_back(get_bubble(in));
  in.get_vec(prev_.label, has_prev_ ? grid_.cells() : -1);
  in.get_vec(prev_.surface, has_prev_ ? grid_.nx : -1);
}

// ---------------------------------------------------------------------------------------------
// The per-frame driver

namespace {
const BubbleSettings& checked(const BubbleSettings& s, const BedGeometry& g) {
  validate(s, g);
  return s;
}
}  // namespace

BubbleAnalysis::BubbleAnalysis(const BubbleSettings& s, const BedGeometry& g)
    : s_(checked(s, g)),
      g_(g),
      field_(make_void_fraction_field(
          make_fine_grid(g.width, g.height, g.thickness, s.cell_size, g.particle_diameter),
          s.window)),
      detector_(s_, g_),
      tracker_(s_, field_.grid) {}

const BubbleFrame& BubbleAnalysis::analyse(double t, const Particles& p) {
  if (started_ && !(t > last_t_))
    throw std::invalid_argument("BubbleAnalysis::analyse: time must increase");
  compute_void_fraction(p, field_);
  frame_.t = t;
  detector_.detect(field_, frame_);
  tracker_.track(frame_);
  history_.add(frame_, started_ ? t - last_t_ : 0.0);
  last_t_ = t;
  started_ = true;
  return frame_;
}

BubbleStatistics BubbleAnalysis::statistics(double averaging_start) const {
  return history_.summarize(averaging_start, std::numeric_limits<double>::infinity(), s_,
                            g_.gravity);
}

Regime BubbleAnalysis::regime(double t_from, double t_to) const {
  return history_.summarize(t_from, t_to, s_, g_.gravity).regime;
}

void BubbleAnalysis::save(std::ostream& out) const {
  put(out, kAnalysisMagic);
  tracker_.save(out);
  put(out, static_cast<std::uint8_t>(started_));
  put(out, last_t_);
  history_.save(out);
}

void BubbleAnalysis::load(std::istream& in_stream, const std::string& origin) {
  BinarySource in(in_stream, origin);
  if (in.get<std::uint32_t>() != kAnalysisMagic) in.fail("inconsistent (bubble analysis)");
  tracker_.load(in_stream, origin);
  started_ = in.get<std::uint8_t>() != 0;
  last_t_ = in.get<double>();
  history_.load(in_stream, origin);
}

void outline_edges(const BubbleFrame& frame, const FineGrid& grid, std::vector<float>& xy) {
  const int nx = grid.nx, ny = grid.ny;
  if (frame.label.size() != static_cast<std::size_t>(grid.cells())) return;
  auto label = [&](int i, int j) {
    return i < 0 || j < 0 || i >= nx || j >= ny ? kCellDense : frame.label[grid.index(i, j)];
  };
  auto edge = [&](double x0, double y0, double x1, double y1) {
    xy.insert(xy.end(), {static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(x1),
                         static_cast<float>(y1)});
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int l = label(i, j);
      if (l < 0) continue;
      const double x0 = i * grid.dx, x1 = (i + 1) * grid.dx;
      const double y0 = j * grid.dy, y1 = (j + 1) * grid.dy;
      if (label(i - 1, j) != l) edge(x0, y0, x0, y1);
      if (label(i + 1, j) != l) edge(x1, y0, x1, y1);
      if (label(i, j - 1) != l) edge(x0, y0, x1, y0);
      if (label(i, j + 1) != l) edge(x0, y1, x1, y1);
    }
}

}  // namespace fluidbed
