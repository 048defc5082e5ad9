// render_options_test.cpp - `holotrace render` option parsing: defaults and values.
#include "cli/render_options.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/error.h"

namespace ht::cli {
namespace {

RenderOptions parse(std::vector<std::string> args) { return parseRenderOptions(args); }

TEST(CliRenderOptions, Defaults) {
  const RenderOptions o = parse({});
  EXPECT_EQ(o.displaySpec, "builtin:portrait");
  EXPECT_EQ(o.sceneSpec, "builtin:showcase");
  EXPECT_FALSE(o.spp.has_value());
  EXPECT_FALSE(o.maxDepth.has_value());
  EXPECT_FALSE(o.png.has_value());
  EXPECT_FALSE(o.exr.has_value());
  EXPECT_EQ(o.outDir, "out");
  EXPECT_EQ(o.deviceIndex, -1);
  EXPECT_FALSE(o.validation);
  EXPECT_EQ(o.seed, 0u);
  EXPECT_FALSE(o.noSpecialize);
}

TEST(CliRenderOptions, EveryOptionIsRead) {
  const RenderOptions o = parse({"--display", "visual.json", "--scene=model.glb", "--spp", "16", "--depth", "0", "-o",
                                 "a/b.PNG", "--exr", "c.exr", "--out-dir", "frames", "--device", "1", "--validation",
                                 "--seed", "4294967295", "--no-specialize"});
  EXPECT_EQ(o.displaySpec, "visual.json");
  EXPECT_EQ(o.sceneSpec, "model.glb");
  EXPECT_EQ(o.spp, 16u);
  EXPECT_EQ(o.maxDepth, 0u);
  EXPECT_EQ(o.png, "a/b.PNG");
  EXPECT_EQ(o.exr, "c.exr");
  EXPECT_EQ(o.outDir, "frames");
  EXPECT_EQ(o.deviceIndex, 1);
  EXPECT_TRUE(o.validation);
  EXPECT_EQ(o.seed, 4294967295u);
  EXPECT_TRUE(o.noSpecialize);
}

TEST(CliRenderOptions, AdaptiveRefinementIsOffUnlessAsked) {
  EXPECT_EQ(parse({}).refineSpp, 0u);
  const RenderOptions o = parse({"--spp", "1", "--refine-spp", "8", "--refine-contrast", "0.05"});
  EXPECT_EQ(o.refineSpp, 8u);
  EXPECT_FLOAT_EQ(o.refineContrast, 0.05f);
  EXPECT_FLOAT_EQ(parse({"--refine-spp", "4"}).refineContrast, gpu::RenderSettings{}.refineContrast);
  EXPECT_THROW(parse({"--refine-contrast", "0.05"}), UsageError);  // a threshold without refinement does nothing
  EXPECT_THROW(parse({"--refine-spp", "4", "--refine-contrast", "1.5"}), UsageError);
  EXPECT_THROW(parse({"--refine-spp", "4097"}), UsageError);
}

TEST(CliRenderOptions, OutOfRangeValuesThrowUsageError) {
  EXPECT_THROW(parse({"--spp", "4097"}), UsageError);
  EXPECT_THROW(parse({"--depth", "33"}), UsageError);
  EXPECT_THROW(parse({"--seed", "4294967296"}), UsageError);
  EXPECT_THROW(parse({"--device", "-1"}), UsageError);
  EXPECT_THROW(parse({"--output", "noextension"}), UsageError);
}

}  // namespace
}  // namespace ht::cli
