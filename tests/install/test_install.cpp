// The installed program: `cmake --install` into a temporary prefix, run from an unrelated folder
// with no $FLUIDBED_ASSETS, finds its scenes and font in PREFIX/share/fluidbed; the Debian package
// declares its dependencies and holds the program, the scenes and the manual page.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

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

bool on_path(const std::string& program) {
  return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0;
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
  const Shell install =
      shell(std::string(FLUIDBED_CMAKE) + " --install '" FLUIDBED_BUILD_DIR "' --prefix '" +
                prefix.string() + "'",
            root, "install");
  ASSERT_EQ(install.status, 0) << install.out;
  const fs::path share = prefix / "share" / "fluidbed";
  EXPECT_TRUE(fs::exists(prefix / "bin" / "fluidbed"));
  EXPECT_TRUE(fs::exists(prefix / "share" / "man" / "man1" / "fluidbed.1.gz"));
  EXPECT_TRUE(fs::exists(share / "fonts" / "DejaVuSans.ttf"));
  for (const std::string& scene : shipped_scenes())
    EXPECT_TRUE(fs::exists(share / "scenes" / scene)) << scene;
  const fs::path doc = prefix / "share" / "doc" / "fluidbed";
  EXPECT_TRUE(fs::exists(doc / "README.md"));
  for (const char* page : {"teaching.md", "running.md", "install.md", "layout.md"})
    EXPECT_TRUE(fs::exists(doc / "docs" / page)) << page;

  // From a folder that has nothing to do with the build or the sources.
  const fs::path work = root / "somewhere" / "else";
  fs::create_directories(work);
  const std::string program = (prefix / "bin" / "fluidbed").string();
  // Its help names the installed documentation.
  const Shell help = shell(program + " --help", work, "help");
  ASSERT_EQ(help.status, 0) << help.out;
  EXPECT_NE(help.out.find("Documentation: " + fs::weakly_canonical(doc).string() + "/README.md"),
            std::string::npos)
      << help.out;
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

#ifdef FLUIDBED_PYTHON_EXE
  // The Python module: under a prefix python3 does not search, the install names the PYTHONPATH
  // to set; from there the module takes its scenes and font from the installed share folder.
  const fs::path site = prefix / "lib" / "python3" / "dist-packages";
  EXPECT_NE(install.out.find("set PYTHONPATH=" + site.string()), std::string::npos) << install.out;
  const Shell py = shell("env PYTHONPATH='" + site.string() + "' " FLUIDBED_PYTHON_EXE
                         " -c \"import fluidbed; s = fluidbed.Simulation(fluidbed.scene('drop')); "
                         "s.step(10); print(fluidbed.__file__); print(fluidbed.scene('drop')); "
                         "s.save_png('py.png', width=320, height=240)\"",
                         work, "python");
  ASSERT_EQ(py.status, 0) << py.out;
  EXPECT_NE(py.out.find((site / "fluidbed" / "__init__.py").string()), std::string::npos)
      << py.out;
  EXPECT_NE(py.out.find((share / "scenes" / "drop.toml").string()), std::string::npos) << py.out;
  EXPECT_GT(fs::file_size(work / "py.png"), 1000u);
#endif
  fs::remove_all(root);
}

TEST(Install, DebianPackageDeclaresItsDependenciesAndHoldsProgramScenesAndManPage) {
  if (!on_path("dpkg-deb") || !on_path("dpkg-shlibdeps") || !fs::exists(FLUIDBED_CPACK))
    GTEST_SKIP() << "cpack, dpkg-deb or dpkg-shlibdeps missing (Debian's cmake and dpkg-dev)";
  const fs::path dir = temp_dir("install-deb");
  // The existing build, packed into a folder of the test's own (nothing is rebuilt).
  const Shell pack = shell(std::string("'") + FLUIDBED_CPACK + "' -G DEB -B '" + dir.string() +
                               "' --config '" FLUIDBED_BUILD_DIR "/CPackConfig.cmake'",
                           dir, "cpack");
  ASSERT_EQ(pack.status, 0) << pack.out;
  fs::path deb;  // fluidbed_VERSION_ARCH.deb
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("fluidbed_" + std::string(FLUIDBED_VERSION) + "_", 0) ==
            0 &&
        e.path().extension() == ".deb")
      deb = e.path();
  ASSERT_FALSE(deb.empty()) << pack.out;

  const Shell info = shell("dpkg-deb --info '" + deb.string() + "'", dir, "info");
  ASSERT_EQ(info.status, 0) << info.out;
  const auto field = [&info](const std::string& name) {
    const auto at = info.out.find("\n " + name + ": ");
    if (at == std::string::npos) return std::string();
    const auto start = at + name.size() + 4;
    return info.out.substr(start, info.out.find('\n', start) - start);
  };
  EXPECT_EQ(field("Package"), "fluidbed");
  EXPECT_EQ(field("Version"), FLUIDBED_VERSION);
  // From the libraries the program links (dpkg-shlibdeps), not a hand-written list.
  const std::string depends = field("Depends");
  for (const char* package :
       {"libc6", "libstdc++6", "libgomp1", "libosmesa6", "libglfw3", "libtomlplusplus3", "zlib1g"})
    EXPECT_NE(depends.find(package), std::string::npos) << package << " not in: " << depends;
  EXPECT_NE(field("Recommends").find("ffmpeg"), std::string::npos) << info.out;

  const Shell list = shell("dpkg-deb -c '" + deb.string() + "'", dir, "list");
  ASSERT_EQ(list.status, 0) << list.out;
  std::set<std::string> files;
  std::istringstream lines(list.out);
  for (std::string line; std::getline(lines, line);) files.insert(line.substr(line.rfind(' ') + 1));
  EXPECT_TRUE(files.count("./usr/bin/fluidbed")) << list.out;
  EXPECT_TRUE(files.count("./usr/share/man/man1/fluidbed.1.gz")) << list.out;
  EXPECT_TRUE(files.count("./usr/share/fluidbed/fonts/DejaVuSans.ttf")) << list.out;
  EXPECT_TRUE(files.count("./usr/share/doc/fluidbed/README.md")) << list.out;
  EXPECT_TRUE(files.count("./usr/share/doc/fluidbed/docs/teaching.md")) << list.out;
  for (const std::string& scene : shipped_scenes())
    EXPECT_TRUE(files.count("./usr/share/fluidbed/scenes/" + scene)) << scene << "\n" << list.out;
  // The shipped beds' U_mf answers, so that the installed viewer opens them at once.
  for (const auto& f : std::filesystem::directory_iterator(std::string(FLUIDBED_ASSET_DIR) + "/umf"))
    EXPECT_TRUE(files.count("./usr/share/fluidbed/umf/" + f.path().filename().string()))
        << f.path() << "\n" << list.out;
#ifdef FLUIDBED_PYTHON_EXE
  // The Python module, where Debian's python3 finds it (/usr/lib/python3/dist-packages).
  EXPECT_TRUE(files.count("./usr/lib/python3/dist-packages/fluidbed/__init__.py")) << list.out;
  bool native = false;
  for (const std::string& f : files)
    native = native || f.rfind("./usr/lib/python3/dist-packages/fluidbed/_core.", 0) == 0;
  EXPECT_TRUE(native) << list.out;
  EXPECT_NE(field("Recommends").find("python3-numpy"), std::string::npos) << info.out;
#endif
  fs::remove_all(dir);
}
