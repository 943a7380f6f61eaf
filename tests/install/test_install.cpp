// The installed program: `cmake --install` into a temporary prefix, run from an unrelated folder
// with no $FLUIDBED_ASSETS, finds its scenes and font in PREFIX/share/fluidbed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "../test_support.hpp"

using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

struct Shell {
  int status;
  std::string out;  // stdout and stderr together
};

// Runs a shell command in `dir` without $FLUIDBED_ASSETS.
Shell shell(const std::string& command, const fs::path& dir, const std::string& tag) {
  const fs::path log = temp_dir("install-log-" + tag) / "log.txt";
  const std::string cmd = "cd '" + dir.string() + "' && env -u FLUIDBED_ASSETS " + command +
                          " > '" + log.string() + "' 2>&1";
  const int raw = std::system(cmd.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_file(log)};
}

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(std::string(FLUIDBED_ASSET_DIR) + "/scenes"))
    if (e.path().extension() == ".toml") names.push_back(e.path().filename().string());
  return names;
}

}  // namespace

TEST(Install, InstalledCopyRunsASceneFromItsShareFolderAndDrawsAFrame) {
  const fs::path root = temp_dir("install-prefix");
  const fs::path prefix = root / "opt" / "fluidbed";
  const Shell install = shell(std::string(FLUIDBED_CMAKE) + " --install '" FLUIDBED_BUILD_DIR
                              "' --prefix '" + prefix.string() + "'", root, "install");
  ASSERT_EQ(install.status, 0) << install.out;
  const fs::path share = prefix / "share" / "fluidbed";
  EXPECT_TRUE(fs::exists(prefix / "bin" / "fluidbed"));
  EXPECT_TRUE(fs::exists(prefix / "share" / "man" / "man1" / "fluidbed.1.gz"));
  EXPECT_TRUE(fs::exists(share / "fonts" / "DejaVuSans.ttf"));
  for (const std::string& scene : shipped_scenes()) EXPECT_TRUE(fs::exists(share / "scenes" / scene)) << scene;

  // From a folder that has nothing to do with the build or the sources.
  const fs::path work = root / "somewhere" / "else";
  fs::create_directories(work);
  const std::string program = (prefix / "bin" / "fluidbed").string();
  const std::string run = program + " run '" + (share / "scenes" / "drop.toml").string() +
                          "' --until 0.02 --frames --frame-interval 0.02 --out out";
  Shell r = shell(run, work, "run");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(fs::exists(work / "out" / "summary.json"));
  const fs::path frame = work / "out" / "frames" / "frame_000001.png";
  ASSERT_TRUE(fs::exists(frame)) << r.out;
  EXPECT_GT(fs::file_size(frame), 1000u);

  // The font it drew with is the installed one: spoilt, the same run names it and stops.
  fs::copy_file(share / "fonts" / "DejaVuSans.ttf", root / "font.ttf");
  write_file(share / "fonts" / "DejaVuSans.ttf", "not a font\n");
  r = shell(run, work, "spoilt-font");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find((share / "fonts" / "DejaVuSans.ttf").string()), std::string::npos) << r.out;
  fs::copy_file(root / "font.ttf", share / "fonts" / "DejaVuSans.ttf",
                fs::copy_options::overwrite_existing);

  // A scene named without a path comes from the installed share folder too: `bench` with no
  // scene runs PREFIX/share/fluidbed/scenes/packing.toml, here replaced by a small one.
  write_file(share / "scenes" / "packing.toml",
             "[scene]\nname = \"installed\"\n[particles]\ncount = 7\n[time]\nend = 0.001\n");
  r = shell(program + " bench --out bench", work, "bench");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(read_file(work / "bench" / "bench.json").find("\"particles\": 7"), std::string::npos)
      << read_file(work / "bench" / "bench.json");
  fs::remove_all(root);
}
