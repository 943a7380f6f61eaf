// The chart library: tick values, where series and lines land in pixels, text, PNG files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "chart/chart.hpp"

using fluidbed::chart::Axis;
using fluidbed::chart::Box;
using fluidbed::chart::Chart;
using fluidbed::chart::Font;
using fluidbed::chart::Image;
using fluidbed::chart::Layout;
using fluidbed::chart::Line;
using fluidbed::chart::Mark;
using fluidbed::chart::Rgb;
using fluidbed::chart::Series;
using fluidbed::chart::Ticks;

namespace {

const Font& font() {
  static const Font f = Font::load_default(FLUIDBED_ASSET_DIR);
  return f;
}

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kRed{200, 0, 0};
constexpr Rgb kBlue{0, 0, 200};

void expect_values(const std::vector<double>& got, const std::vector<double>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 0; k < want.size(); ++k) {
    EXPECT_NEAR(got[k], want[k], 1e-12 * std::max(1.0, std::abs(want[k]))) << "tick " << k;
  }
}

// A plain chart on [0, 10] x [0, 10]: no grid, no legend, so pixels are series or background.
Chart bare() {
  Chart c;
  c.x = {"x", false, 0.0, 10.0};
  c.y = {"y", false, 0.0, 10.0};
  c.grid = false;
  c.legend = false;
  return c;
}

Series line(std::vector<double> x, std::vector<double> y, Rgb colour, double width = 3.0) {
  Series s;
  s.x = std::move(x);
  s.y = std::move(y);
  s.colour = colour;
  s.width = width;
  return s;
}

int pixel(double v) {
  return static_cast<int>(std::floor(v));
}

// Pixels of exactly COLOUR inside BOX.
int count(const Image& img, Rgb colour, const Box& box) {
  int n = 0;
  for (int y = std::max(0, pixel(box.y0)); y < std::min(img.height(), pixel(box.y1)); ++y) {
    for (int x = std::max(0, pixel(box.x0)); x < std::min(img.width(), pixel(box.x1)); ++x) {
      if (img.at(x, y) == colour) ++n;
    }
  }
  return n;
}

std::vector<unsigned char> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(ChartTicks, LinearStepsAreOneTwoFive) {
  Ticks t = fluidbed::chart::linear_ticks(0.0, 10.0, 6);
  expect_values(t.major, {0, 2, 4, 6, 8, 10});
  EXPECT_EQ(t.labels.front(), "0");
  EXPECT_EQ(t.labels.back(), "10");

  // 0.2 gives 6 ticks (1 off the target of 5), 0.5 gives 3 (2 off).
  t = fluidbed::chart::linear_ticks(0.0, 1.0, 5);
  expect_values(t.major, {0, 0.2, 0.4, 0.6, 0.8, 1.0});
  EXPECT_EQ(t.labels[3], "0.6");  // 3 x 0.2 printed without a rounding tail

  // Step 2 gives 8 ticks in [-3.7, 12.1], step 5 gives 3; target 6.
  t = fluidbed::chart::linear_ticks(-3.7, 12.1, 6);
  expect_values(t.major, {-2, 0, 2, 4, 6, 8, 10, 12});
  EXPECT_EQ(t.labels[0], "−2");  // a true minus sign
  EXPECT_TRUE(t.multiplier.empty());

  // 0.001 and 0.002 both miss the target of 5 by 2 (3 and 7 ticks): the larger step wins.
  t = fluidbed::chart::linear_ticks(0.0012, 0.0047, 5);
  expect_values(t.major, {0.002, 0.003, 0.004});
  EXPECT_EQ(t.labels[0], "0.002");

  // Millions and hundred-thousandths share a power of ten.
  t = fluidbed::chart::linear_ticks(0.0, 3e6, 4);
  expect_values(t.major, {0, 1e6, 2e6, 3e6});
  EXPECT_EQ(t.multiplier, "×10⁶");
  EXPECT_EQ(t.labels[2], "2");
  t = fluidbed::chart::linear_ticks(0.0, 5e-5, 6);
  expect_values(t.major, {0, 1e-5, 2e-5, 3e-5, 4e-5, 5e-5});
  EXPECT_EQ(t.multiplier, "×10⁻⁵");
  EXPECT_EQ(t.labels[4], "4");
}

TEST(ChartTicks, LogAxesUseDecades) {
  Ticks t = fluidbed::chart::log_ticks(1e-3, 1e2, 8);
  expect_values(t.major, {1e-3, 1e-2, 1e-1, 1, 10, 100});
  EXPECT_EQ(t.labels.front(), "10⁻³");
  EXPECT_EQ(t.labels.back(), "10²");
  EXPECT_EQ(t.minor.size(), 5u * 8u);  // 2..9 in each of the five whole decades

  // Thirteen decades, at most five labels: every third decade, on multiples of three.
  t = fluidbed::chart::log_ticks(1e-6, 1e6, 5);
  expect_values(t.major, {1e-6, 1e-3, 1, 1e3, 1e6});
  EXPECT_EQ(t.minor.size(), 8u);  // the decades in between

  // Under two decades: 1, 2 and 5 x 10^k.
  t = fluidbed::chart::log_ticks(2.0, 40.0, 6);
  expect_values(t.major, {2, 5, 10, 20});
  EXPECT_EQ(t.labels[1], "5");
  expect_values(t.minor, {3, 4, 6, 7, 8, 9, 30, 40});

  // Not even one of those inside: a linear scale.
  t = fluidbed::chart::log_ticks(3.0, 4.0, 5);
  expect_values(t.major, {3.0, 3.5, 4.0});
}

TEST(ChartRender, SeriesColourLandsOnItsPoints) {
  Chart c = bare();
  c.series = {line({0, 10}, {0, 10}, kRed)};
  Series dot = line({5}, {2}, kBlue);
  dot.mark = Mark::Points;
  dot.marker_size = 9;
  c.series.push_back(dot);
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  const Image img = fluidbed::chart::render(c, 800, 500, font());
  for (double v = 1.0; v <= 9.0; v += 1.0) {
    const double x = l.map.px(v), y = l.map.py(v);
    // A 3 px line covers every pixel whose centre is within 1 px of it in full.
    EXPECT_EQ(img.at(pixel(x), pixel(y)), kRed) << "on the line at " << v;
    // 12 px to the side is 8.5 px from the diagonal line: background.
    EXPECT_EQ(img.at(pixel(x + 12), pixel(y)), kWhite) << "beside the line at " << v;
    EXPECT_EQ(img.at(pixel(x - 12), pixel(y)), kWhite) << "beside the line at " << v;
  }
  const double x = l.map.px(5), y = l.map.py(2);
  EXPECT_EQ(img.at(pixel(x), pixel(y)), kBlue);
  EXPECT_EQ(img.at(pixel(x + 2), pixel(y - 2)), kBlue);  // inside the 4.5 px radius
  EXPECT_EQ(img.at(pixel(x + 8), pixel(y)), kWhite);
  EXPECT_EQ(img.at(pixel(x), pixel(y + 8)), kWhite);
  // The axis maps 0..10 onto the plot box edge to edge.
  EXPECT_DOUBLE_EQ(l.map.px(0), l.plot.x0);
  EXPECT_DOUBLE_EQ(l.map.px(10), l.plot.x1);
  EXPECT_DOUBLE_EQ(l.map.py(0), l.plot.y1);
  EXPECT_DOUBLE_EQ(l.map.py(10), l.plot.y0);
}

TEST(ChartRender, HorizontalLineCoversItsRow) {
  Chart c = bare();
  c.hlines = {{3.0, "", kBlue, false, 1.0}};
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  const Image img = fluidbed::chart::render(c, 800, 500, font());
  const int row = pixel(l.map.py(3.0));
  const int x0 = pixel(l.plot.x0), x1 = pixel(l.plot.x1);
  // A solid 1 px line on a pixel centre: the whole row, nothing above or below.
  EXPECT_EQ(count(img, kBlue, {l.plot.x0, row + 0.0, l.plot.x1, row + 1.0}), x1 - x0);
  EXPECT_EQ(count(img, kBlue, {l.plot.x0, row - 3.0, l.plot.x1, row + 0.0}), 0);
  EXPECT_EQ(count(img, kBlue, {l.plot.x0, row + 1.0, l.plot.x1, row + 4.0}), 0);
}

TEST(ChartRender, SizeAndSameBytesTwice) {
  Chart c;
  c.title = "twice";
  c.x.label = "t (s)";
  c.y.label = "Δp (Pa)";
  Series s;
  s.label = "a";
  s.mark = Mark::LinePoints;
  for (int k = 0; k < 200; ++k) {
    s.x.push_back(0.01 * k);
    s.y.push_back(std::sin(0.1 * k));
  }
  c.series = {s};
  const Image a = fluidbed::chart::render(c, 640, 400, font());
  const Image b = fluidbed::chart::render(c, 640, 400, font());
  EXPECT_EQ(a.width(), 640);
  EXPECT_EQ(a.height(), 400);
  EXPECT_EQ(a.pixels().size(), 640u * 400u * 3u);
  EXPECT_TRUE(a.pixels() == b.pixels());
  EXPECT_TRUE(a.encode_png() == b.encode_png());
}

TEST(ChartRender, NanLeavesAGap) {
  Chart c = bare();
  std::vector<double> x, y;
  for (int k = 0; k <= 10; ++k) {
    x.push_back(k);
    y.push_back(k == 5 ? std::numeric_limits<double>::quiet_NaN() : 5.0);
  }
  c.series = {line(x, y, kRed, 2.0)};
  // Series that must not crash: empty, all NaN, infinities.
  const double inf = std::numeric_limits<double>::infinity();
  c.series.push_back(line({}, {}, kBlue));
  c.series.push_back(line({1, 2}, {std::nan(""), std::nan("")}, kBlue));
  c.series.push_back(line({1, inf, 3}, {-inf, 2, 1e300}, kBlue));
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  const Image img = fluidbed::chart::render(c, 800, 500, font());
  const int row = pixel(l.map.py(5.0));
  // The line runs on both sides of the missing point and not across it: x in (4, 6) is 2
  // plot-widths / 10 = 140 px wide, the round end reaches 1 px past x = 4 and x = 6.
  EXPECT_EQ(img.at(pixel(l.map.px(2.0)), row), kRed);
  EXPECT_EQ(img.at(pixel(l.map.px(8.0)), row), kRed);
  EXPECT_EQ(count(img, kRed, {l.map.px(4.0) + 3, row - 3.0, l.map.px(6.0) - 3, row + 3.0}), 0);
}

TEST(ChartRender, ConstantAndEmptyDataGetASpan) {
  Chart c;
  c.series = {line({0, 1, 2}, {3, 3, 3}, kRed)};
  Layout l = fluidbed::chart::layout(c, 800, 500, font());
  EXPECT_LT(l.map.y_lo, 3.0);
  EXPECT_GT(l.map.y_hi, 3.0);
  EXPECT_GE(l.y_ticks.major.size(), 2u);
  EXPECT_EQ(fluidbed::chart::render(c, 800, 500, font()).width(), 800);

  Chart empty;
  empty.y.log = true;
  l = fluidbed::chart::layout(empty, 800, 500, font());
  EXPECT_LT(l.map.x_lo, l.map.x_hi);
  EXPECT_GT(l.map.y_lo, 0.0);
  EXPECT_GE(l.y_ticks.major.size(), 2u);
}

TEST(ChartRender, PointsOutsideExplicitBoundsAreClipped) {
  Chart c = bare();
  Series s = line({-5, 5, 20, 5}, {5, 5, 30, -40}, kRed, 4.0);
  s.mark = Mark::LinePoints;
  c.series = {s};
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  const Image img = fluidbed::chart::render(c, 800, 500, font());
  const int inside = count(img, kRed, l.plot);
  EXPECT_GT(inside, 100);
  EXPECT_EQ(count(img, kRed, {0, 0, 800, 500}), inside);  // none outside the plot box
}

TEST(ChartRender, TinyImagesAndExtremeValuesDoNotBreak) {
  Chart c;
  c.title = "a title wider than the image";
  c.x.label = "x";
  c.y.label = "y";
  Series s = line({-1e300, 0, 1e300}, {1e-300, 1, 1e300}, kRed);
  s.label = "extreme";
  s.mark = Mark::LinePoints;
  s.point_labels = {"a", "b", "c"};
  s.y_error = {1e300, 0.5, std::nan("")};
  c.series = {s};
  c.hlines = {{1.0, "one", kBlue, true, 1.5}};
  for (const bool log : {false, true}) {
    c.y.log = log;
    for (const auto& [w, h] : {std::pair{1, 1}, {40, 30}, {100, 60}, {3000, 200}}) {
      const Image img = fluidbed::chart::render(c, w, h, font());
      EXPECT_EQ(img.width(), w);
      EXPECT_EQ(img.height(), h);
      const Layout l = fluidbed::chart::layout(c, w, h, font());
      EXPECT_GE(l.plot.width(), 1.0);
      EXPECT_GE(l.plot.height(), 1.0);
      EXPECT_LT(l.map.y_lo, l.map.y_hi);
    }
  }
}

TEST(ChartRender, EqualAspectMakesAMetreTheSameLength) {
  Chart c;
  c.x = {"x (m)", false, 0.0, 0.15};
  c.y = {"y (m)", false, 0.0, 0.9};
  c.equal_aspect = true;
  c.series = {line({0.01, 0.14}, {0.1, 0.8}, kRed)};
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  const double per_x = (l.map.px(0.15) - l.map.px(0.0)) / 0.15;
  const double per_y = (l.map.py(0.0) - l.map.py(0.9)) / 0.9;
  EXPECT_NEAR(per_x, per_y, 1.0 / 0.15);  // the box is rounded to whole pixels
  EXPECT_LT(l.plot.width(), 0.3 * l.plot.height());
}

TEST(ChartRender, LegendAvoidsTheData) {
  Chart c = bare();
  Series s = line({6, 7, 8, 9, 6, 9}, {6, 7, 8, 9, 9, 6}, kRed);
  s.mark = Mark::Points;
  s.label = "upper right";
  c.legend = true;
  c.series = {s};
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  ASSERT_GT(l.legend.width(), 0.0);
  for (std::size_t k = 0; k < s.x.size(); ++k) {
    EXPECT_FALSE(l.legend.contains(l.map.px(s.x[k]), l.map.py(s.y[k]))) << "point " << k;
  }
  EXPECT_TRUE(l.plot.contains(l.legend.x0, l.legend.y0));
  EXPECT_TRUE(l.plot.contains(l.legend.x1, l.legend.y1));
}

TEST(ChartRender, BadInputIsRefusedInWords) {
  Chart c;
  c.title = "sweep";
  Series s = line({1, 2, 3}, {1, 2}, kRed);
  s.label = "up";
  c.series = {s};
  try {
    fluidbed::chart::render(c, 800, 500, font());
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"up\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("3 x values but 2 y values"), std::string::npos);
  }
  Chart log;
  log.x = {"", true, 0.0, 10.0};
  EXPECT_THROW(fluidbed::chart::layout(log, 800, 500, font()), std::invalid_argument);
  EXPECT_THROW(Image(0, 10), std::invalid_argument);
}

TEST(ChartText, TitleInkIsInTheTitleBox) {
  Chart c = bare();
  c.title = "Pressure drop against time";
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  ASSERT_GT(l.title.width(), 100.0);
  ASSERT_GT(l.title.height(), 10.0);
  EXPECT_LT(l.title.y1, l.plot.y0);
  const Image img = fluidbed::chart::render(c, 800, 500, font());
  int ink = 0, dark = 0, total = 0;
  for (int y = pixel(l.title.y0); y < pixel(l.title.y1); ++y) {
    for (int x = pixel(l.title.x0); x < pixel(l.title.x1); ++x) {
      const Rgb p = img.at(x, y);
      ++total;
      if (!(p == kWhite)) ++ink;
      if (p.r < 100 && p.g < 100 && p.b < 100) ++dark;
    }
  }
  // Letters cover some 15-30% of their line's box; most of it solid, the rest anti-aliased.
  EXPECT_GT(ink, total / 10);
  EXPECT_LT(ink, total * 6 / 10);
  EXPECT_GT(dark, total / 20);
  // No title: an empty box, and no ink above the plot.
  c.title.clear();
  const Layout none = fluidbed::chart::layout(c, 800, 500, font());
  EXPECT_EQ(none.title.width(), 0.0);
  const Image plain = fluidbed::chart::render(c, 800, 500, font());
  EXPECT_EQ(count(plain, kWhite, {0, 0, 800, none.plot.y0 - 12}), 800 * pixel(none.plot.y0 - 12));
}

TEST(ChartText, PointLabelsAreDrawnNextToTheirPoints) {
  Chart c = bare();
  Series s = line({2, 5, 8}, {2, 5, 8}, kRed);
  s.mark = Mark::Points;
  c.series = {s};
  const Layout l = fluidbed::chart::layout(c, 800, 500, font());
  const Image without = fluidbed::chart::render(c, 800, 500, font());
  c.series[0].point_labels = {"dt=1e-4", "dt=5e-5", "dt=2e-5"};
  const Image with = fluidbed::chart::render(c, 800, 500, font());
  for (std::size_t k = 0; k < 3; ++k) {
    const double x = l.map.px(s.x[k]), y = l.map.py(s.y[k]);
    const Box near{x - 80, y - 30, x + 80, y + 30};
    EXPECT_GT(count(without, kWhite, near) - count(with, kWhite, near), 100) << "point " << k;
  }
}

TEST(ChartFont, MissingFontNamesEveryPathTried) {
  try {
    Font::load({"/nonexistent/a.ttf", "/nonexistent/b.ttf"});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/nonexistent/a.ttf"), std::string::npos) << what;
    EXPECT_NE(what.find("/nonexistent/b.ttf"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  // A file that is not a font is passed over for the next path, and said so if none is left.
  const auto junk = std::filesystem::temp_directory_path() /
                    ("fluidbed_test_chart_junk." + std::to_string(::getpid()) + ".ttf");
  std::ofstream(junk) << "not a font at all\n";
  EXPECT_EQ(Font::load({junk.string(), font().path()}).path(), font().path());
  try {
    Font::load({junk.string()});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not a TrueType font"), std::string::npos) << e.what();
  }
  std::filesystem::remove(junk);
  const std::vector<std::string> paths = fluidbed::chart::font_search_paths("/src/assets");
  ASSERT_GE(paths.size(), 2u);
  EXPECT_EQ(paths[paths.size() - 2], "/src/assets/fonts/DejaVuSans.ttf");
  EXPECT_EQ(paths.back(), "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
}

TEST(ChartPng, FileHasSignatureAndSize) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("fluidbed_test_chart." + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "small.png").string();
  Image img(37, 21, {10, 20, 30});
  img.set(3, 4, {255, 0, 0});
  img.write_png(path);
  const std::vector<unsigned char> bytes = read_bytes(path);
  ASSERT_GE(bytes.size(), 33u);
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  for (int k = 0; k < 8; ++k) EXPECT_EQ(bytes[k], signature[k]) << "byte " << k;
  EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
  const auto be32 = [&bytes](std::size_t at) {
    return (std::uint32_t{bytes[at]} << 24) | (std::uint32_t{bytes[at + 1]} << 16) |
           (std::uint32_t{bytes[at + 2]} << 8) | std::uint32_t{bytes[at + 3]};
  };
  EXPECT_EQ(be32(16), 37u);
  EXPECT_EQ(be32(20), 21u);
  EXPECT_EQ(bytes[24], 8);  // bits per channel
  EXPECT_EQ(bytes[25], 2);  // RGB
  std::filesystem::remove_all(dir);
}

TEST(ChartPng, BadPathThrowsNamingIt) {
  const std::string path = "/nonexistent-folder/sub/chart.png";
  try {
    Image(4, 4).write_png(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(ChartGrid, PanelsFillRowByRow) {
  Chart a = bare();
  a.series = {line({0, 10}, {5, 5}, kRed)};
  Chart b = bare();
  b.series = {line({0, 10}, {5, 5}, kBlue)};
  const Image img = fluidbed::chart::render_grid({a, b, a}, 2, 400, 250, font());
  EXPECT_EQ(img.width(), 800);
  EXPECT_EQ(img.height(), 500);
  EXPECT_GT(count(img, kRed, {0, 0, 400, 250}), 100);
  EXPECT_GT(count(img, kBlue, {400, 0, 800, 250}), 100);
  EXPECT_GT(count(img, kRed, {0, 250, 400, 500}), 100);
  EXPECT_EQ(count(img, kWhite, {400, 250, 800, 500}), 400 * 250);  // no fourth panel
  const Image titled = fluidbed::chart::render_grid({a, b}, 2, 400, 250, font(), "Two panels");
  EXPECT_GT(titled.height(), 250);
  EXPECT_THROW(fluidbed::chart::render_grid({}, 2, 400, 250, font()), std::invalid_argument);
}

// A figure of panels of different shapes: each where it was put, all at one text scale (a tall
// narrow panel's text as large as a wide one's), the figure as large as the panels reach.
TEST(ChartFigure, PanelsGoWhereTheyArePutAtOneScale) {
  Chart a = bare();
  a.series = {line({0, 10}, {5, 5}, kRed)};
  Chart b = bare();
  b.series = {line({0, 10}, {5, 5}, kBlue)};
  const Image img = fluidbed::chart::render_figure({{a, 0, 0, 300, 800}, {b, 300, 0, 900, 400}},
                                                   1.2, font());
  EXPECT_EQ(img.width(), 1200);
  EXPECT_EQ(img.height(), 800);
  EXPECT_GT(count(img, kRed, {0, 0, 300, 800}), 100);
  EXPECT_EQ(count(img, kRed, {300, 0, 1200, 800}), 0);
  EXPECT_GT(count(img, kBlue, {300, 0, 1200, 400}), 100);
  EXPECT_EQ(count(img, kWhite, {300, 400, 1200, 800}), 900 * 400);  // nothing below the second
  // The scale asked for, not the one the narrow panel's size would give (min(300/800, ...)).
  EXPECT_DOUBLE_EQ(fluidbed::chart::layout(a, 300, 800, font(), 1.2).scale, 1.2);
  EXPECT_DOUBLE_EQ(fluidbed::chart::layout(a, 300, 800, font()).scale, 300.0 / 800.0);
  const Image titled = fluidbed::chart::render_figure({{a, 0, 0, 300, 800}}, 1.2, font(), "T");
  EXPECT_GT(titled.height(), 800);
}
