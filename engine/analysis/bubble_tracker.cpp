// Bubbles followed from frame to frame: ids, velocities and events
// (analysis/bubble_tracker.hpp says the rules).
#include "analysis/bubble_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace fluidbed {

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
  // surface than its largest size (see the top of bubble_tracker.hpp).
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

}  // namespace fluidbed
