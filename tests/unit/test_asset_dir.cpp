// Where the program finds its assets: $FLUIDBED_ASSETS, then an installed copy's share folder
// beside its own path, then the source tree's (render/asset_dir.hpp).
#include <gtest/gtest.h>

#include <filesystem>

#include "../test_support.hpp"
#include "render/asset_dir.hpp"

using fluidbed::render::find_asset_dir;
using fluidbed::render::source_asset_dir;

TEST(AssetDir, EnvironmentWinsThenInstalledShareThenSourceTree) {
  const auto prefix = fluidbed::testing::temp_dir("asset-dir");
  const auto program = prefix / "bin" / "fluidbed";
  // No share folder yet: the source tree's assets, which hold the shipped scenes.
  EXPECT_EQ(find_asset_dir(nullptr, program), source_asset_dir());
  EXPECT_TRUE(std::filesystem::exists(source_asset_dir() + "/scenes/drop.toml"));
  EXPECT_EQ(std::filesystem::path(source_asset_dir()), std::filesystem::path(FLUIDBED_ASSET_DIR));
  // A share folder without scenes/ is not an installed copy.
  std::filesystem::create_directories(prefix / "bin");
  std::filesystem::create_directories(prefix / "share" / "fluidbed" / "fonts");
  EXPECT_EQ(find_asset_dir(nullptr, program), source_asset_dir());
  std::filesystem::create_directories(prefix / "share" / "fluidbed" / "scenes");
  EXPECT_EQ(find_asset_dir(nullptr, program), (prefix / "share" / "fluidbed").string());
  // The variable wins over both; set but empty counts as unset.
  EXPECT_EQ(find_asset_dir("/elsewhere/assets", program), "/elsewhere/assets");
  EXPECT_EQ(find_asset_dir("", program), (prefix / "share" / "fluidbed").string());
  EXPECT_EQ(find_asset_dir("", ""), source_asset_dir());
  std::filesystem::remove_all(prefix);
}
