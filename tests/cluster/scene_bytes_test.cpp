// Scene bytes: what rank 0 broadcasts decodes to the same scene (every field), and damaged bytes are refused.
#include <gtest/gtest.h>

#include "cluster/cluster_error.h"
#include "cluster/scene_bytes.h"

namespace ht::cluster {
namespace {

TEST(SceneBytes, ABuiltinSceneWithEveryKindOfDataSurvivesTheRoundTrip) {
  const Scene scene = loadScene("builtin:showcase");  // materials, a texture, lights, nodes
  ASSERT_FALSE(scene.textures.empty());
  ASSERT_FALSE(scene.lights.empty());
  ASSERT_FALSE(scene.nodes.empty());
  const std::vector<std::uint8_t> bytes = encodeScene(scene);
  const Scene back = decodeScene(bytes);
  EXPECT_EQ(encodeScene(back), bytes);
  EXPECT_EQ(back.name, scene.name);
  EXPECT_EQ(back.positions, scene.positions);
  EXPECT_EQ(back.triangles, scene.triangles);
  EXPECT_EQ(back.materials.size(), scene.materials.size());
  EXPECT_EQ(back.materials.back().name, scene.materials.back().name);
  EXPECT_EQ(back.materials.back().ior, scene.materials.back().ior);
  EXPECT_EQ(back.textures.front().texels, scene.textures.front().texels);
  EXPECT_EQ(back.lights.back().position, scene.lights.back().position);
  EXPECT_EQ(back.lights.back().type, scene.lights.back().type);
  EXPECT_EQ(back.nodes.back().name, scene.nodes.back().name);
  EXPECT_EQ(back.nodes.back().world, scene.nodes.back().world);
  EXPECT_EQ(back.background, scene.background);
  EXPECT_EQ(back.bounds().lo, scene.bounds().lo);
}

TEST(SceneBytes, TruncatedOrPaddedBytesAreRefused) {
  const std::vector<std::uint8_t> bytes = encodeScene(loadScene("builtin:plain"));
  for (const std::size_t keep : {std::size_t{0}, std::size_t{5}, bytes.size() / 2, bytes.size() - 1}) {
    EXPECT_THROW(decodeScene(std::span(bytes.data(), keep)), ClusterError) << keep << " bytes";
  }
  std::vector<std::uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_THROW(decodeScene(longer), ClusterError);
  std::vector<std::uint8_t> huge = bytes;
  for (int i = 0; i < 8; ++i) huge[i] = 0xff;  // the length of the name, the first field
  EXPECT_THROW(decodeScene(huge), ClusterError);
}

}  // namespace
}  // namespace ht::cluster
