// output_paths_test.cpp - default output names of `holotrace render`.
#include "cli/output_paths.h"

#include <gtest/gtest.h>

namespace ht::cli {
namespace {

TEST(CliOutputPaths, TokensAreFileNameSafe) {
  EXPECT_EQ(fileNameToken("builtin:showcase"), "showcase");
  EXPECT_EQ(fileNameToken("/data/scenes/My Bunny (v2).glb"), "my_bunny_v2");
  EXPECT_EQ(fileNameToken("portrait"), "portrait");
  EXPECT_EQ(fileNameToken("gen3-16-landscape"), "gen3-16-landscape");
  EXPECT_EQ(fileNameToken("../../etc/passwd"), "passwd");
  EXPECT_EQ(fileNameToken("???"), "unnamed");
}

TEST(CliOutputPaths, DefaultsGoToOutDirWithDisplayAndSceneNames) {
  RenderOptions options;
  const OutputPaths paths = resolveOutputPaths(options, "portrait");
  EXPECT_EQ(paths.png, std::filesystem::path("out/portrait_showcase.png"));
  EXPECT_EQ(paths.exr, std::filesystem::path("out/portrait_showcase.exr"));
  options.outDir = "frames";
  options.sceneSpec = "assets/bunny.obj";
  EXPECT_EQ(resolveOutputPaths(options, "Looking Glass 16").png,
            std::filesystem::path("frames/looking_glass_16_bunny.png"));
}

TEST(CliOutputPaths, ExplicitPathsReplaceTheDefaults) {
  RenderOptions options;
  options.png = "x.png";
  OutputPaths paths = resolveOutputPaths(options, "portrait");
  EXPECT_EQ(paths.png, std::filesystem::path("x.png"));
  EXPECT_FALSE(paths.exr.has_value());
  options.png.reset();
  options.exr = "y.exr";
  paths = resolveOutputPaths(options, "portrait");
  EXPECT_FALSE(paths.png.has_value());
  EXPECT_EQ(paths.exr, std::filesystem::path("y.exr"));
}

}  // namespace
}  // namespace ht::cli
