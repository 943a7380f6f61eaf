// `fluidbed run --frames --video --vtk --montage --bubble-outlines` on a short coupled run (300
// particles, 0.02 s): the files exist in the right number and size, the video decodes (ffprobe)
// with the right frame count, the VTK series (particles, gas, the fine void fraction) reads back
// (a small reader of the format here, and VTK's own readers when Debian's python3-vtk9 is
// installed), and frame output leaves summary.json's numbers unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <set>

#include "../test_support.hpp"
#include "io/vtk_writer.hpp"
#include "output/plots.hpp"
#include "sim/simulation.hpp"
#include "render_support.hpp"

using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

// 300 particles on the lattice start in the paper's bed with its jet: a few seconds of work.
std::string short_run(const fs::path& out) {
  return "run " + std::string(FLUIDBED_ASSET_DIR) +
         "/scenes/xu_yu_1997.toml --until 0.02 --set particles.placement=lattice"
         " --set particles.count=300 --set particles.fill_height=0.2 --out " + out.string();
}
constexpr int kFrames = 5;  // t = 0, 0.005, 0.01, 0.015, 0.02
constexpr double kInterval = 0.005;
constexpr double kDt = 1.5e-5;

class RunOutputs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = temp_dir("run-outputs");
    with_ = run_fluidbed(short_run(root_ / "with") +
                             " --frames --video --vtk --montage 0.01,0.02 --frame-interval 0.005"
                             " --frame-size 320x240 --colour force --bubble-outlines",
                         "outputs-with");
    without_ = run_fluidbed(short_run(root_ / "without"), "outputs-without");
  }
  static fs::path root_;
  static CommandResult with_, without_;
};
fs::path RunOutputs::root_;
CommandResult RunOutputs::with_, RunOutputs::without_;

std::pair<int, int> png_size(const fs::path& p) {
  const std::string bytes = read_file(p);
  if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0) return {-1, -1};
  auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned char>(bytes[at]) << 24) | (static_cast<unsigned char>(bytes[at + 1]) << 16) |
           (static_cast<unsigned char>(bytes[at + 2]) << 8) | static_cast<unsigned char>(bytes[at + 3]);
  };
  return {be32(16), be32(20)};
}

std::string capture(const std::string& command) {
  std::string out;
  FILE* p = popen(command.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  pclose(p);
  return out;
}

// --- a small reader of the VTK XML files this program writes ----------------------------------

// The value of name="..." in a tag's text (empty when absent). Plain string search: std::regex
// trips GCC 12's maybe-uninitialized warning under the sanitizers.
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return {};
  const std::size_t from = at + key.size();
  return tag.substr(from, tag.find('"', from) - from);
}

// Each element `<name ...>` or `<name .../>` of `xml`: its attribute text, and the text up to the
// closing tag when it has one.
std::vector<std::pair<std::string, std::string>> elements(const std::string& xml, const std::string& name) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::string open = "<" + name + " ", close = "</" + name + ">";
  for (std::size_t at = xml.find(open); at != std::string::npos; at = xml.find(open, at + 1)) {
    const std::size_t end = xml.find('>', at);
    std::string tag = xml.substr(at, end - at);
    std::string body;
    if (!tag.empty() && tag.back() != '/') {
      const std::size_t stop = xml.find(close, end);
      body = xml.substr(end + 1, stop - end - 1);
    }
    out.emplace_back(std::move(tag), std::move(body));
  }
  return out;
}

std::vector<std::uint8_t> from_base64(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    int v = c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26
            : c >= '0' && c <= '9' ? c - '0' + 52 : c == '+' ? 62 : c == '/' ? 63 : -1;
    if (v < 0) continue;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((acc >> bits) & 0xFF));
    }
  }
  return out;
}

struct Array {
  std::string type;
  int components = 1;
  std::vector<double> values;
};

// Every named <DataArray> of a file, decoded (binary: UInt32 byte count, then the values).
std::map<std::string, Array> read_arrays(const fs::path& p) {
  std::map<std::string, Array> arrays;
  const std::string xml = read_file(p);
  for (const auto& [tag, body] : elements(xml, "DataArray")) {
    Array a;
    a.type = attribute(tag, "type");
    const std::string nc = attribute(tag, "NumberOfComponents");
    a.components = nc.empty() ? 1 : std::stoi(nc);
    if (attribute(tag, "format") == "binary") {
      const auto raw = from_base64(body);
      std::uint32_t bytes = 0;
      std::memcpy(&bytes, raw.data(), 4);
      EXPECT_EQ(bytes + 4, raw.size()) << p;
      const std::size_t size = a.type == "Float64" ? 8 : 4;
      for (std::size_t k = 4; k + size <= raw.size(); k += size) {
        if (a.type == "Float32") {
          float f;
          std::memcpy(&f, raw.data() + k, 4);
          a.values.push_back(f);
        } else if (a.type == "Int32") {
          std::int32_t i;
          std::memcpy(&i, raw.data() + k, 4);
          a.values.push_back(i);
        } else {
          double d;
          std::memcpy(&d, raw.data() + k, 8);
          a.values.push_back(d);
        }
      }
    } else {
      a.values.push_back(std::stod(body));
    }
    const std::string name = attribute(tag, "Name");
    arrays[name.empty() ? "Points" : name] = a;
  }
  return arrays;
}

// (time, file) of a .pvd collection.
std::vector<std::pair<double, std::string>> read_collection(const fs::path& p) {
  std::vector<std::pair<double, std::string>> out;
  for (const auto& [tag, body] : elements(read_file(p), "DataSet"))
    out.emplace_back(std::stod(attribute(tag, "timestep")), attribute(tag, "file"));
  return out;
}

}  // namespace

// The particles' points: a thick bed's at the snapshot's z, a monolayer's on the mid-plane.
TEST(VtkParticles, PointsAreAtTheSnapshotsDepth) {
  const fs::path dir = temp_dir("vtk-depth");
  fluidbed::Snapshot s = empty_box();
  s.thickness = 0.02;
  add_particle(s, {0.01, 0.02, 0.002});
  add_particle(s, {0.03, 0.04, 0.002});
  s.z = {0.0035, 0.0162};
  fluidbed::write_particles_vtp((dir / "thick.vtp").string(), s);
  const auto thick = read_arrays(dir / "thick.vtp").at("Points").values;
  ASSERT_EQ(thick.size(), 6u);
  const double want[] = {0.01, 0.02, 0.0035, 0.03, 0.04, 0.0162};
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(thick[k], want[k], 1e-8) << k;
  s.z.clear();
  fluidbed::write_particles_vtp((dir / "monolayer.vtp").string(), s);
  const auto mono = read_arrays(dir / "monolayer.vtp").at("Points").values;
  ASSERT_EQ(mono.size(), 6u);
  EXPECT_NEAR(mono[2], 0.01, 1e-8);
  EXPECT_NEAR(mono[5], 0.01, 1e-8);
}

// A thick bed's vectors carry their parts across the slab and about x and y: velocity (vx, vy,
// vz), force (fx, fy, fz), spin and torque (about x, y, z). A monolayer's have 0 there.
TEST(VtkParticles, AThickBedsVectorsHaveTheirPartsAcrossTheSlab) {
  const fs::path dir = temp_dir("vtk-depth-vectors");
  fluidbed::Snapshot s = empty_box();
  s.thickness = 0.02;
  add_particle(s, {0.01, 0.02, 0.002, 0.1, 0.2, 0.3, 0.4, 5e-5});
  add_particle(s, {0.03, 0.04, 0.002, -0.1, -0.2, -0.3, -0.4, -5e-5});
  s.spin = {7.0, -7.0};
  s.z = {0.0035, 0.0162};
  s.vz = {0.25, -0.5};
  s.fz = {1e-3, -2e-3};
  s.spin_x = {1.0, 2.0};
  s.spin_y = {3.0, 4.0};
  s.torque_x = {1e-5, 2e-5};
  s.torque_y = {3e-5, 4e-5};
  fluidbed::write_particles_vtp((dir / "thick.vtp").string(), s);
  const auto thick = read_arrays(dir / "thick.vtp");
  const std::map<std::string, std::vector<double>> want = {
      {"velocity", {0.1, 0.2, 0.25, -0.1, -0.2, -0.5}},
      {"force", {0.3, 0.4, 1e-3, -0.3, -0.4, -2e-3}},
      {"spin", {1.0, 3.0, 7.0, 2.0, 4.0, -7.0}},
      {"torque", {1e-5, 3e-5, 5e-5, 2e-5, 4e-5, -5e-5}}};
  for (const auto& [name, values] : want) {
    const auto& got = thick.at(name).values;
    ASSERT_EQ(got.size(), 6u) << name;
    for (std::size_t k = 0; k < 6; ++k)
      EXPECT_NEAR(got[k], values[k], 1e-7 * std::abs(values[k])) << name << " " << k;
  }
  for (auto* v : {&s.z, &s.vz, &s.fz, &s.spin_x, &s.spin_y, &s.torque_x, &s.torque_y}) v->clear();
  fluidbed::write_particles_vtp((dir / "monolayer.vtp").string(), s);
  const auto mono = read_arrays(dir / "monolayer.vtp");
  EXPECT_EQ(mono.at("velocity").values[2], 0.0);
  EXPECT_EQ(mono.at("force").values[5], 0.0);
  EXPECT_EQ(mono.at("spin").values[0], 0.0);
  EXPECT_EQ(mono.at("torque").values[4], 0.0);
  EXPECT_NEAR(mono.at("torque").values[5], -5e-5, 1e-7 * 5e-5);  // Float32 in the file
}

// A snapshot's bytes give it back whole, a thick bed's parts across the slab and a plenum's
// depth included; one saved before those parts existed (version 3: without the plenum; version
// 2: without the slab's parts either) loads with them empty or 0.
TEST(SnapshotBytes, RoundTripKeepsTheSlabsPartsAndReadsVersion2) {
  fluidbed::Snapshot s = empty_box();
  add_particle(s, {0.01, 0.02, 0.002, 0.1, 0.2, 0.3, 0.4, 5e-5});
  s.z = {0.0035};
  s.vz = {0.25};
  s.fz = {1e-3};
  s.spin_x = {1.0};
  s.spin_y = {3.0};
  s.torque_x = {1e-5};
  s.torque_y = {3e-5};
  s.gas_bottom = -0.04;
  std::ostringstream out;
  fluidbed::save_snapshot(out, s);
  std::istringstream in(out.str());
  fluidbed::BinarySource src(in, "test");
  fluidbed::Snapshot back;
  fluidbed::load_snapshot(src, back);
  EXPECT_EQ(back.z, s.z);
  EXPECT_EQ(back.gas_bottom, -0.04);
  EXPECT_EQ(back.vz, s.vz);
  EXPECT_EQ(back.fz, s.fz);
  EXPECT_EQ(back.spin_x, s.spin_x);
  EXPECT_EQ(back.spin_y, s.spin_y);
  EXPECT_EQ(back.torque_x, s.torque_x);
  EXPECT_EQ(back.torque_y, s.torque_y);
  EXPECT_EQ(back.vx, s.vx);

  // Version 3: tag ...'3', and no plenum's depth at the end (8 bytes).
  std::string bytes = out.str();
  ASSERT_EQ(bytes.substr(0, 8), "FLBSNAP4");
  bytes[7] = '3';
  bytes.resize(bytes.size() - 8);
  {
    std::istringstream in3(bytes);
    fluidbed::BinarySource src3(in3, "test");
    fluidbed::Snapshot v3;
    v3.gas_bottom = -1.0;  // a reused snapshot: set by the load
    fluidbed::load_snapshot(src3, v3);
    EXPECT_EQ(v3.gas_bottom, 0.0);
    EXPECT_EQ(v3.vz, s.vz);
  }
  // Version 2: tag ...'2', and no six arrays at the end either (each an empty array is its
  // 8-byte length alone).
  for (auto* v : {&s.vz, &s.fz, &s.spin_x, &s.spin_y, &s.torque_x, &s.torque_y}) v->clear();
  std::ostringstream v4;
  fluidbed::save_snapshot(v4, s);
  bytes = v4.str();
  bytes[7] = '2';
  bytes.resize(bytes.size() - 6 * 8 - 8);
  std::istringstream in2(bytes);
  fluidbed::BinarySource src2(in2, "test");
  fluidbed::Snapshot old;
  old.vz = {9.0};  // a reused buffer: cleared by the load
  fluidbed::load_snapshot(src2, old);
  EXPECT_TRUE(old.vz.empty());
  EXPECT_EQ(old.z, s.z);
  EXPECT_EQ(old.x, s.x);
  // Anything else is refused.
  bytes[7] = '1';
  std::istringstream in3(bytes);
  fluidbed::BinarySource src3(in3, "test");
  EXPECT_THROW(fluidbed::load_snapshot(src3, old), std::exception);
}

TEST_F(RunOutputs, FramesHaveTheRightCountAndSize) {
  ASSERT_EQ(with_.status, 0) << with_.err;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(root_ / "with" / "frames")) names.push_back(e.path().filename());
  std::sort(names.begin(), names.end());
  ASSERT_EQ(names.size(), static_cast<std::size_t>(kFrames));
  for (int k = 0; k < kFrames; ++k) {
    char want[32];
    std::snprintf(want, sizeof want, "frame_%06d.png", k);
    EXPECT_EQ(names[static_cast<std::size_t>(k)], want);
    EXPECT_EQ(png_size(root_ / "with" / "frames" / want), std::make_pair(320, 240)) << want;
  }
  // The montage: two panels side by side, the frame height tall.
  const auto montage = png_size(root_ / "with" / "montage.png");
  EXPECT_EQ(montage.second, 240);
  EXPECT_GT(montage.first, 100);
  // Nothing half-written left behind.
  for (const auto& e : fs::recursive_directory_iterator(root_ / "with"))
    EXPECT_EQ(e.path().string().find(".part"), std::string::npos) << e.path();
}

TEST_F(RunOutputs, VideoDecodesWithTheRightFrameCount) {
  ASSERT_EQ(with_.status, 0) << with_.err;
  const fs::path video = root_ / "with" / "video.mp4";
  ASSERT_TRUE(fs::exists(video));
  const std::string probe = capture(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=codec_name,width,height,nb_read_frames -of json " + video.string());
  const auto j = nlohmann::json::parse(probe);
  const auto& s = j.at("streams").at(0);
  EXPECT_EQ(s.at("codec_name"), "h264");
  EXPECT_EQ(s.at("width"), 320);
  EXPECT_EQ(s.at("height"), 240);
  EXPECT_EQ(std::stoi(s.at("nb_read_frames").get<std::string>()), kFrames);
}

TEST_F(RunOutputs, FrameOutputLeavesTheSummaryUnchanged) {
  ASSERT_EQ(with_.status, 0) << with_.err;
  ASSERT_EQ(without_.status, 0) << without_.err;
  auto a = nlohmann::json::parse(read_file(root_ / "with" / "summary.json"));
  auto b = nlohmann::json::parse(read_file(root_ / "without" / "summary.json"));
  // Wall-clock measurements differ from run to run; every number of the physics must not.
  for (auto* j : {&a, &b})
    for (auto it = j->begin(); it != j->end();)
      it = it.key().find("wall") != std::string::npos || it.key().find("per_s") != std::string::npos ||
                   it.key().find("timer") != std::string::npos
               ? j->erase(it)
               : std::next(it);
  EXPECT_EQ(a, b);
  EXPECT_EQ(read_file(root_ / "with" / "timeseries.csv"), read_file(root_ / "without" / "timeseries.csv"));
  EXPECT_FALSE(a.at("state_hash").get<std::string>().empty());
}

TEST_F(RunOutputs, VtkSeriesReadsBack) {
  ASSERT_EQ(with_.status, 0) << with_.err;
  const fs::path vtk = root_ / "with" / "vtk";
  const auto particles = read_collection(vtk / "particles.pvd");
  const auto gas = read_collection(vtk / "gas.pvd");
  ASSERT_EQ(particles.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(gas.size(), static_cast<std::size_t>(kFrames));
  const auto summary = nlohmann::json::parse(read_file(root_ / "with" / "summary.json"));
  const int n = summary.at("particles").get<int>();
  ASSERT_EQ(n, 300);
  for (int k = 0; k < kFrames; ++k) {
    // Times: the nearest step to k x interval.
    EXPECT_NEAR(particles[static_cast<std::size_t>(k)].first, k * kInterval, 0.5 * kDt + 1e-12);
    EXPECT_EQ(gas[static_cast<std::size_t>(k)].first, particles[static_cast<std::size_t>(k)].first);
    const auto p = read_arrays(vtk / particles[static_cast<std::size_t>(k)].second);
    std::set<std::string> names;
    for (const auto& [name, a] : p) names.insert(name);
    EXPECT_EQ(names, (std::set<std::string>{"Points", "TimeValue", "velocity", "force", "torque",
                                            "spin", "overlap", "radius", "initial_height", "id",
                                            "connectivity", "offsets"}));
    EXPECT_EQ(p.at("Points").values.size(), 3u * n);
    EXPECT_EQ(p.at("velocity").values.size(), 3u * n);
    EXPECT_EQ(p.at("id").values.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(p.at("id").values.back(), n - 1);
    EXPECT_NEAR(p.at("radius").values.front(), 0.002, 1e-9);
    EXPECT_EQ(p.at("TimeValue").values.front(), particles[static_cast<std::size_t>(k)].first);
    const auto g = read_arrays(vtk / gas[static_cast<std::size_t>(k)].second);
    EXPECT_EQ(g.at("velocity").values.size(), 3u * 15 * 45);
    EXPECT_EQ(g.at("pressure").values.size(), 15u * 45);
    for (double eps : g.at("porosity").values) {
      EXPECT_GT(eps, 0.2);
      EXPECT_LE(eps, 1.0 + 1e-6);
    }
  }
  // The bubble analysis' fine void fraction beside them: a 2 mm grid over the bed, values in
  // [0, 1], holding the spheres' volume (each sphere's volume shared among the cells it covers).
  const auto voids = read_collection(vtk / "void.pvd");
  ASSERT_EQ(voids.size(), static_cast<std::size_t>(kFrames));
  for (int k = 0; k < kFrames; ++k) {
    EXPECT_EQ(voids[static_cast<std::size_t>(k)].first, particles[static_cast<std::size_t>(k)].first);
    const auto v = read_arrays(vtk / voids[static_cast<std::size_t>(k)].second);
    const auto& eps = v.at("void_fraction").values;
    ASSERT_EQ(eps.size(), 75u * 450u);
    double solid = 0.0;
    for (double e : eps) {
      EXPECT_GE(e, -1e-6);
      EXPECT_LE(e, 1.0 + 1e-6);
      solid += (1.0 - e) * 0.002 * 0.002 * 0.004;
    }
    const double spheres = n * 4.0 / 3.0 * M_PI * 0.002 * 0.002 * 0.002;
    EXPECT_NEAR(solid, spheres, 1e-3 * spheres);
  }
  // ParaView's readers (VTK's own) open every file of the series: counts and names agree.
  if (std::system("/usr/bin/python3 -c 'import vtk' 2>/dev/null") != 0)
    GTEST_SKIP() << "python3-vtk9 is not installed (scripts/install-deps.sh installs it)";
  const std::string script = R"PY(
import sys, re, vtk
d = sys.argv[1]
for kind, reader in (("particles", vtk.vtkXMLPolyDataReader), ("gas", vtk.vtkXMLImageDataReader),
                     ("void", vtk.vtkXMLImageDataReader)):
    text = open(f"{d}/{kind}.pvd").read()
    for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text):
        r = reader(); r.SetFileName(f"{d}/{f}"); r.Update(); o = r.GetOutput()
        data = o.GetPointData() if kind == "particles" else o.GetCellData()
        names = sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))
        count = o.GetNumberOfPoints() if kind == "particles" else o.GetNumberOfCells()
        time = o.GetFieldData().GetArray("TimeValue").GetValue(0)
        print(kind, t, count, ",".join(names), repr(time))
)PY";
  write_file(root_ / "read.py", script);
  const std::string out = capture("/usr/bin/python3 " + (root_ / "read.py").string() + " " + vtk.string());
  std::istringstream lines(out);
  std::string kind, t, names, time;
  int count = 0, seen = 0;
  while (lines >> kind >> t >> count >> names >> time) {
    ++seen;
    if (kind == "particles") {
      EXPECT_EQ(count, n);
      EXPECT_EQ(names, "force,id,initial_height,overlap,radius,spin,torque,velocity");
    } else if (kind == "gas") {
      EXPECT_EQ(count, 15 * 45);
      EXPECT_EQ(names, "porosity,pressure,velocity");
    } else {
      EXPECT_EQ(kind, "void");
      EXPECT_EQ(count, 75 * 450);
      EXPECT_EQ(names, "void_fraction");
    }
    EXPECT_DOUBLE_EQ(std::stod(t), std::stod(time));
  }
  EXPECT_EQ(seen, 3 * kFrames) << out;
}

TEST(RunOutputOptions, BadValuesAreRefusedInOneLine) {
  const auto dir = temp_dir("run-output-options");
  const std::string base = short_run(dir / "o");
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : {Case{" --frames --colour temperature", "temperature"},
                        Case{" --frames --frame-size 12x", "--frame-size"},
                        Case{" --montage 0.01,5", "--montage"},
                        Case{" --video --frame-size 321x240", "even"},
                        Case{" --frames --gl-backend vulkan", "osmesa"}}) {
    const CommandResult r = run_fluidbed(base + c.args, "run-output-options");
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o" / "summary.json")) << c.args;
  }
}

TEST(TrackedParticles, AreFollowedByIdWhenTheSolverRenumbers) {
  // `--plots`' trajectories (Figs 12-13): the particles nearest two points at the start, followed
  // through renumberings by cell (every 100 steps here) by their ids.
  fluidbed::Settings s;
  s.scene.kind = fluidbed::SceneKind::Packing;
  s.domain.width = 0.06;
  s.domain.height = 0.2;
  s.particles.count = 300;
  s.contact.renumber_steps = 100;
  fluidbed::Simulation sim(s);
  const std::vector<int> ids = fluidbed::app::nearest_particles(sim.dem(), {{0.01, 0.02}, {0.05, 0.1}});
  const fluidbed::Particles start = sim.dem().exported_state().particles;  // in ids
  const double at[2][2] = {{0.01, 0.02}, {0.05, 0.1}};
  for (std::size_t k = 0; k < ids.size(); ++k) {
    auto d2 = [&](std::size_t i) {
      return std::pow(start.x[i] - at[k][0], 2) + std::pow(start.y[i] - at[k][1], 2);
    };
    for (std::size_t i = 0; i < start.size(); ++i)
      ASSERT_GE(d2(i), d2(static_cast<std::size_t>(ids[k])));
  }
  fluidbed::app::TrajectoryRecorder tracks(ids, 0.0, s.time.dt);
  for (int k = 0; k < 2500; ++k) {
    sim.step();
    tracks.observe(sim);
  }
  ASSERT_TRUE(sim.dem().renumbered());
  const fluidbed::DemState now = sim.dem().exported_state();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const fluidbed::app::Trajectory& t = tracks.tracks()[k];
    ASSERT_EQ(t.x.size(), 2500u);
    EXPECT_EQ(t.x.back(), now.particles.x[static_cast<std::size_t>(ids[k])]);
    EXPECT_EQ(t.y.back(), now.particles.y[static_cast<std::size_t>(ids[k])]);
  }
}
