// Bubble statistics, output, settings and checkpoints on synthetic particle sets: a packed
// hexagonal monolayer with circular holes cut out (bubble_test_bed.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/bubbles.hpp"
#include "bubble_test_bed.hpp"
#include "core/binary_io.hpp"
#include "core/errors.hpp"
#include "scene/lattice.hpp"


TEST(BubbleStatistics, MeansOverBubbleFramesAndThePyleHarrisonReference) {
  // A hole of D_e 20 mm (removal radius 12 mm) rising 6.93 mm per 10 ms from t = 0.01 s; averaging
  // from 0.025 s.
  BubbleAnalysis a({}, {});
  for (int k = 0; k < 6; ++k)
    a.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, {{0.07, 0.05 + 2 * k * kRow, 0.010}}));
  const fluidbed::BubbleStatistics st = a.statistics(0.025);
  EXPECT_EQ(st.frames, 4);  // t = 0.03 .. 0.06
  EXPECT_EQ(st.bubble_frames, 4);
  EXPECT_EQ(st.velocity_samples, 4);
  const double d_eq = expected_d_eq({{0.07, 0.05, 0.010}});
  EXPECT_NEAR(st.mean_d_eq_m, d_eq, 0.05 * d_eq);
  EXPECT_NEAR(st.mean_rise_velocity_m_s, 2 * kRow / 0.01, 0.03 * 2 * kRow / 0.01);
  EXPECT_NEAR(st.mean_rise_velocity_2d_ref_m_s, 0.5 * std::sqrt(9.81 * st.mean_d_eq_m), 0.002);
  EXPECT_EQ(st.formed, 0);  // formed at t = 0.01, before the window
  EXPECT_EQ(st.slugging_fraction, 0.0);
  EXPECT_EQ(st.regime, Regime::fixed);  // nothing formed in the window
  // The first frame has no interval before it: its bubble's `formed` counts in no window.
  EXPECT_EQ(a.regime(0.0, 1.0), Regime::fixed);
  const nlohmann::json j = fluidbed::to_json(st);
  for (const char* key : {"formed_per_s", "eruptions_per_s", "mean_d_eq_m",
                          "mean_rise_velocity_m_s", "slugging_fraction", "regime"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["regime"], "fixed");
  EXPECT_NEAR(j["mean_d_eq_m"].get<double>(), st.mean_d_eq_m, 1e-15);
  // No bubble at all: means are null, not 0.
  BubbleAnalysis empty({}, {});
  empty.analyse(0.01, hex_bed(kWidth, kTop));
  empty.analyse(0.02, hex_bed(kWidth, kTop));
  const nlohmann::json e = fluidbed::to_json(empty.statistics(0.0));
  EXPECT_TRUE(e["mean_d_eq_m"].is_null());
  EXPECT_TRUE(e["mean_rise_velocity_m_s"].is_null());
  EXPECT_EQ(e["regime"], "fixed");
  EXPECT_EQ(e["formed_per_s"], 0.0);
}

// The fault: the regime label said "fixed bed" over the expanded, moving bed of the ideal-vs-real
// lesson. A bed without bubbles that has risen at least a diameter (4 mm) above its first frame
// and whose median sphere moves at least a diameter a second is `expanded`; risen but still (a
// bed left loose by a higher velocity), or moving in place, it is `fixed`.
TEST(BubbleStatistics, ABedThatMovesAndHasRisenWithoutBubblesIsExpanded) {
  const auto run = [](double top, double speed) {
    BubbleAnalysis a({}, {});
    a.analyse(0.01, hex_bed(kWidth, kTop));  // the packed bed: the reference surface
    for (int k = 1; k <= 20; ++k) {
      fluidbed::Particles p = hex_bed(kWidth, top);
      for (std::size_t i = 0; i < p.size(); ++i) {  // half the spheres at `speed`, half faster
        p.vx[i] = i % 2 == 0 ? 0.6 * speed : 3.0 * speed;
        p.vy[i] = i % 2 == 0 ? 0.8 * speed : 0.0;
      }
      a.analyse(0.01 * (k + 1), p);
      EXPECT_NEAR(a.frame().median_speed, p.size() % 2 == 0 ? 3.0 * speed : speed, 1e-12);
    }
    return a.statistics(0.0);
  };
  const double d = 0.004;
  const fluidbed::BubbleStatistics risen = run(kTop + 5 * kRow, 0.05);
  EXPECT_EQ(risen.formed, 0);
  EXPECT_NEAR(risen.bed_rise_m, 5 * kRow, 0.5 * d);
  EXPECT_EQ(risen.regime, Regime::expanded);
  EXPECT_EQ(fluidbed::to_json(risen)["regime"], "expanded");
  EXPECT_GT(fluidbed::to_json(risen)["median_particle_speed_m_s"].get<double>(), 0.05 - 1e-12);
  EXPECT_EQ(run(kTop + 5 * kRow, 0.0).regime, Regime::fixed);  // loose but still
  EXPECT_EQ(run(kTop + 5 * kRow, 0.002).regime, Regime::fixed);  // slower than d per second
  EXPECT_EQ(run(kTop, 0.05).regime, Regime::fixed);               // moving in place
  EXPECT_STREQ(fluidbed::to_string(Regime::expanded), "expanded");

  // An analysis started again in the same run measures from the first one's surface.
  BubbleAnalysis first({}, {});
  first.analyse(0.01, hex_bed(kWidth, kTop - 4 * kRow));
  BubbleAnalysis again({}, {});
  again.set_reference_surface(first.history().reference_surface);
  for (int k = 0; k < 5; ++k) again.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop));
  EXPECT_NEAR(again.statistics(0.0).bed_rise_m, 4 * kRow, 0.5 * d);
}

TEST(BubbleStatistics, RegimeRule) {
  // 100 frames of 10 ms after a first one; each case sets what the rule looks at: bubbles formed
  // (ids seen in 3 frames), frames with a slug, frames with the jet open to the freeboard.
  const BubbleSettings s;
  const auto history = [](int formed, int slug, int spout) {
    BubbleHistory h;
    h.frames.push_back({0.0, 0.0, false, false, true});
    for (int k = 0; k < 100; ++k) {
      const double t = 0.01 * (k + 1);
      h.frames.push_back({t, 0.01, k < slug, k < spout, true});
      if (k < formed) {
        BubbleHistory::Sample q;
        q.t = t;
        q.id = k;
        q.d_eq = 0.02;
        q.event = BubbleEvent::formed;
        h.samples.push_back(q);
        h.id_frames.push_back(3);
      }
    }
    return h;
  };
  constexpr double inf = std::numeric_limits<double>::infinity();
  const auto regime = [&](int formed, int slug, int spout, double t0 = 0.0,
                          double t1 = std::numeric_limits<double>::infinity()) {
    return history(formed, slug, spout).summarize(t0, t1, s, 9.81).regime;
  };
  EXPECT_EQ(regime(0, 0, 0), Regime::fixed);
  EXPECT_EQ(regime(3, 0, 0), Regime::bubbling);
  EXPECT_EQ(regime(3, 10, 0), Regime::bubbling);
  EXPECT_EQ(regime(0, 5, 0), Regime::bubbling);
  EXPECT_EQ(regime(3, 25, 0), Regime::slugging);
  EXPECT_EQ(regime(0, 0, 50), Regime::spouting);
  EXPECT_EQ(regime(3, 60, 49), Regime::slugging);
  const auto st = history(3, 25, 0).summarize(0.0, inf, s, 9.81);
  EXPECT_EQ(st.frames, 100);
  EXPECT_NEAR(st.duration, 1.0, 1e-12);
  EXPECT_NEAR(st.slugging_fraction, 0.25, 1e-12);
  EXPECT_NEAR(st.formed_per_s, 3.0, 1e-9);
  EXPECT_NEAR(st.jet_cavity_fraction, 1.0, 1e-12);
  // Per window: the first 0.25 s hold the slugs and the bubbles.
  EXPECT_EQ(regime(3, 25, 0, 0.0, 0.25), Regime::slugging);
  EXPECT_EQ(regime(3, 25, 0, 0.5, 1.0), Regime::fixed);
  // Ids seen in fewer than min_track_frames frames are flicker: not counted.
  BubbleHistory flicker = history(3, 0, 0);
  flicker.id_frames = {1, 2, 3};
  const auto f = flicker.summarize(0.0, inf, s, 9.81);
  EXPECT_EQ(f.formed, 1);
  EXPECT_EQ(f.flicker_ids, 2);
  EXPECT_STREQ(fluidbed::to_string(Regime::spouting), "spouting");
}

TEST(BubbleStatistics, ForgettingWhatNoLaterWindowReadsKeepsEveryWindowsSummary) {
  // The viewer's regime: a trailing window of 0.3 s summarised after each of 1,000 frames of
  // 10 ms, its history forgetting what lies before the window each time, against the whole
  // history. Samples of every event, some with a velocity, ids of 1 to 5 frames, slugs and
  // spouts here and there (a seeded generator).
  const BubbleSettings s;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BubbleHistory whole, trailing;
  std::size_t largest = 0;
  int next_id = 0;
  for (int k = 0; k < 1000; ++k) {
    const double t = 0.01 * k;
    BubbleHistory::Frame f;
    f.t = t;
    f.dt = k == 0 ? 0.0 : 0.01;
    f.slug = unit(rng) < 0.2;
    f.spout = unit(rng) < 0.1;
    f.jet_cavity = unit(rng) < 0.5;
    f.surface = 0.1 + 0.01 * unit(rng);
    f.median_speed = unit(rng);
    std::vector<BubbleHistory::Sample> qs(static_cast<std::size_t>(4 * unit(rng)));
    for (BubbleHistory::Sample& q : qs) {
      q.t = t;
      q.id = next_id++;
      q.d_eq = 0.01 + 0.02 * unit(rng);
      q.vx = unit(rng) - 0.5;
      q.vy = unit(rng);
      q.has_velocity = unit(rng) < 0.7;
      q.from_jet = unit(rng) < 0.3;
      q.event = static_cast<BubbleEvent>(static_cast<int>(6 * unit(rng)) % 6);
      q.merged_id = q.event == BubbleEvent::coalesced ? q.id / 2 : -1;
      q.ended = q.event == BubbleEvent::erupted || q.event == BubbleEvent::vanished;
      whole.id_frames.push_back(1 + static_cast<int>(5 * unit(rng)) % 5);
    }
    for (BubbleHistory* h : {&whole, &trailing}) {
      h->frames.push_back(f);
      h->samples.insert(h->samples.end(), qs.begin(), qs.end());
      h->reference_surface = 0.1;
    }
    trailing.id_frames = whole.id_frames;
    const double from = std::max(0.0, t - 0.3);
    const std::string a = to_json(whole.summarize(from, t, s, 9.81)).dump();
    const std::string b = to_json(trailing.summarize(from, t, s, 9.81)).dump();
    ASSERT_EQ(a, b) << "at t = " << t;
    trailing.forget_before(from);
    largest = std::max(largest, trailing.frames.size());
  }
  EXPECT_EQ(whole.frames.size(), 1000u);
  // Within twice the window's 31 frames, and one frame before it.
  EXPECT_LE(largest, 63u);
  EXPECT_LT(trailing.samples.size(), whole.samples.size() / 10);
}

TEST(BubbleStatistics, FlickerEruptionAndBursts) {
  // Frame by frame on synthetic beds (0.12 m deep): a hole seen in one frame only is flicker; a
  // bubble just under the surface that fills in (its roof, 18 mm, thinner than its 21 mm) has
  // erupted; two such bubbles ending 10 ms apart are one burst; a bubble deep in the bed that
  // fills in has vanished.
  const double top = 0.12;
  BubbleAnalysis a({}, {});
  std::vector<BubbleRow> rows;
  const std::vector<std::vector<Hole>> frames = {
      {},
      {{0.04, 0.05, 0.008}},                        // flicker: one frame
      {{0.04, 0.095, 0.011}, {0.11, 0.03, 0.010}},  // near the surface; deep
      {{0.04, 0.095, 0.011}, {0.11, 0.03, 0.010}, {0.11, 0.095, 0.011}},
      {{0.04, 0.095, 0.011}, {0.11, 0.03, 0.010}, {0.11, 0.095, 0.011}},
      {{0.11, 0.03, 0.010}, {0.11, 0.095, 0.011}},  // the first fills in: erupted
      {},                                           // both others fill in
  };
  for (std::size_t k = 0; k < frames.size(); ++k) {
    a.analyse(0.01 * static_cast<double>(k + 1), hex_bed(kWidth, top, frames[k]));
    a.append_rows(rows);
  }
  int erupted = 0, vanished = 0;
  for (const BubbleRow& r : rows) {
    if (r.event == BubbleEvent::erupted) {
      ++erupted;
      EXPECT_GT(r.y, 0.08);
    }
    if (r.event == BubbleEvent::vanished) {
      ++vanished;
      EXPECT_LT(r.y, 0.08);
    }
  }
  EXPECT_EQ(erupted, 2);
  EXPECT_EQ(vanished, 2);  // the flicker and the deep one
  const fluidbed::BubbleStatistics st = a.statistics(0.0);
  EXPECT_EQ(st.flicker_ids, 1);
  EXPECT_EQ(st.formed, 3);
  EXPECT_EQ(st.erupted, 2);
  EXPECT_EQ(st.vanished, 1);
  EXPECT_EQ(st.eruption_bursts, 1);  // 10 ms apart, within eruption_gap
  EXPECT_NEAR(st.eruptions_per_s, 1.0 / 0.06, 1e-9);
  EXPECT_NEAR(st.erupted_bubbles_per_s, 2.0 / 0.06, 1e-9);
}

TEST(BubbleCsv, OneRowPerBubbleWithTheIssuesColumns) {
  std::vector<BubbleRow> rows(2);
  rows[0] = {0.25, 3, 0.075, 0.1, 0.024, 4.5e-4, 0.026, 0.022, 0.01, 0.35, true, BubbleEvent::none};
  rows[1] = {0.25, 4, 0.05, 0.12, 0.01, 8e-5, 0.01, 0.01, 0.0, 0.0, false, BubbleEvent::split};
  std::ostringstream os;
  fluidbed::write_bubbles_csv_header(os);
  fluidbed::write_bubbles_csv_rows(os, rows);
  EXPECT_EQ(os.str(),
            "t,id,x,y,d_eq,area,width,height,vx,vy,event\n"
            "0.25,3,0.075,0.1,0.024,0.00045,0.026,0.022,0.01,0.35,\n"
            "0.25,4,0.05,0.12,0.01,8e-05,0.01,0.01,,,split\n");
}

TEST(BubbleSettings, BadParametersAreOneLineInputErrorsNamingTheKey) {
  const BedGeometry g;
  const auto expect_error = [&](BubbleSettings s, const std::string& key) {
    try {
      BubbleAnalysis a(s, g);
      ADD_FAILURE() << "no error for " << key;
    } catch (const fluidbed::InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(key + " ", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  for (double t : {0.0, 1.0, -0.2, 1.5, std::nan("")}) {
    BubbleSettings s;
    s.threshold = t;
    expect_error(s, "bubbles.threshold");
  }
  for (double i : {0.0, -0.01, std::nan("")}) {
    BubbleSettings s;
    s.interval = i;
    expect_error(s, "bubbles.interval");
  }
  BubbleSettings s;
  s.min_diameter = -0.001;
  expect_error(s, "bubbles.min_diameter");
  s = BubbleSettings{};
  s.slug_fraction = 0.0;
  expect_error(s, "bubbles.slug_fraction");
  s = BubbleSettings{};
  s.cell_size = 0.0;
  expect_error(s, "bubbles.cell_size");
  // The defaults for another particle size.
  const BubbleSettings d = fluidbed::default_bubble_settings(0.002);
  EXPECT_DOUBLE_EQ(d.min_diameter, 0.004);
  EXPECT_DOUBLE_EQ(d.cell_size, 0.001);
  EXPECT_NO_THROW(fluidbed::validate(BubbleSettings{}, g));
}

TEST(BubbleAnalysis, CheckpointResumesWithTheSameResults) {
  // Frames 1-3, a checkpoint, frames 4-6: the same rows and statistics as 1-6 in one go.
  const auto holes = [](int k) {
    return std::vector<Hole>{{0.05, 0.04 + 2 * k * kRow, 0.010}, {0.11, 0.16 - 0.004 * k, 0.012}};
  };
  BubbleAnalysis whole({}, {});
  std::vector<BubbleRow> whole_rows;
  for (int k = 0; k < 6; ++k) {
    whole.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, holes(k)));
    if (k >= 3) whole.append_rows(whole_rows);
  }
  BubbleAnalysis first({}, {});
  for (int k = 0; k < 3; ++k) first.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, holes(k)));
  std::stringstream state;
  fluidbed::BinarySink sink(state);
  first.save(sink);
  BubbleAnalysis resumed({}, {});
  const std::string origin = "checkpoint";
  fluidbed::BinarySource source(state, origin);
  resumed.restore(source);
  std::vector<BubbleRow> resumed_rows;
  for (int k = 3; k < 6; ++k) {
    resumed.analyse(0.01 * (k + 1), hex_bed(kWidth, kTop, holes(k)));
    resumed.append_rows(resumed_rows);
  }
  std::ostringstream a, b;
  fluidbed::write_bubbles_csv_rows(a, whole_rows);
  fluidbed::write_bubbles_csv_rows(b, resumed_rows);
  EXPECT_FALSE(whole_rows.empty());
  EXPECT_EQ(a.str(), b.str());
  EXPECT_EQ(fluidbed::to_json(whole.statistics(0.0)).dump(),
            fluidbed::to_json(resumed.statistics(0.0)).dump());
  // A truncated state is an InputError naming its origin.
  std::stringstream cut(state.str().substr(0, 40));
  BubbleAnalysis broken({}, {});
  fluidbed::BinarySource cut_source(cut, origin);
  EXPECT_THROW(broken.restore(cut_source), fluidbed::InputError);
}

TEST(BubbleAnalysis, CheckpointOfAnotherLayoutOrGridIsRefusedInOneLine) {
  BubbleAnalysis a({}, {});
  a.analyse(0.01, hex_bed(kWidth, kTop, {{0.05, 0.08, 0.010}}));
  std::stringstream saved;
  fluidbed::BinarySink sink(saved);
  a.save(sink);
  const std::string origin = "run/checkpoint.bin";
  const auto refusal = [&](BubbleAnalysis& into, const std::string& bytes) {
    std::stringstream in(bytes);
    fluidbed::BinarySource source(in, origin);
    try {
      into.restore(source);
    } catch (const fluidbed::InputError& e) {
      return std::string(e.what());
    }
    return std::string("restored");
  };
  // The same settings: restored.
  BubbleAnalysis same({}, {});
  EXPECT_EQ(refusal(same, saved.str()), "restored");
  // An analysis on another fine grid: the tracker's cell labels do not fit it.
  BubbleSettings coarse;
  coarse.cell_size = 0.004;
  BubbleAnalysis other(coarse, {});
  EXPECT_EQ(refusal(other, saved.str()),
            "run/checkpoint.bin: state file is inconsistent (array sizes)");
  // Another version of the section (its tag's last two characters).
  std::string older = saved.str();
  older[6] = '0';
  older[7] = '1';
  BubbleAnalysis fresh({}, {});
  EXPECT_EQ(refusal(fresh, older),
            "run/checkpoint.bin: state file is written by another version of fluidbed (bubble "
            "analysis 01, this one reads 03): run it again from its start");
  // The layout before the tags (a four-byte magic number, then the tracker's).
  std::string legacy = saved.str();
  legacy.replace(0, 8, std::string("AHUB1BUB"));
  BubbleAnalysis fresh2({}, {});
  EXPECT_EQ(refusal(fresh2, legacy), "run/checkpoint.bin: state file is not a bubble analysis's");
}
