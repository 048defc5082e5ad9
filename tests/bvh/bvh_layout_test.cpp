// bvh_layout_test.cpp - Bvh2 -> GpuBvh conversion: node packing, triangle slots, single-leaf and empty trees.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "bvh/bvh_traversal.h"
#include "bvh/gpu_layout.h"
#include "bvh_test_util.h"
#include "common/error.h"

namespace ht::bvh {
namespace {

using gpu_shared::GpuBvhNode;
using gpu_shared::HT_TRI_STRIDE;

glm::vec3 childLo(const GpuBvhNode& n, int k) {
  return k == 0 ? glm::vec3(n.c0xy.x, n.c0xy.z, n.c01z.x) : glm::vec3(n.c1xy.x, n.c1xy.z, n.c01z.z);
}
glm::vec3 childHi(const GpuBvhNode& n, int k) {
  return k == 0 ? glm::vec3(n.c0xy.y, n.c0xy.w, n.c01z.y) : glm::vec3(n.c1xy.y, n.c1xy.w, n.c01z.w);
}
bool isEmptyChild(const GpuBvhNode& n, int k) {
  glm::vec3 lo = childLo(n, k), hi = childHi(n, k);
  return glm::all(glm::equal(lo, glm::vec3(INFINITY))) && glm::all(glm::equal(hi, glm::vec3(-INFINITY)));
}

void expectSlotsHoldPrimIndex(const GpuBvh& gpu, const Bvh2& bvh, const test::Mesh& mesh) {
  ASSERT_EQ(gpu.triangles.size(), bvh.primIndex.size() * HT_TRI_STRIDE);
  for (size_t slot = 0; slot < bvh.primIndex.size(); ++slot) {
    const uint32_t id = bvh.primIndex[slot];
    const glm::uvec3& tri = mesh.triangles[id];
    for (int v = 0; v < 3; ++v) {
      const glm::vec4& stored = gpu.triangles[slot * HT_TRI_STRIDE + v];
      EXPECT_EQ(glm::vec3(stored), mesh.positions[tri[v]]);
    }
    EXPECT_EQ(glm::floatBitsToUint(gpu.triangles[slot * HT_TRI_STRIDE].w), id);
  }
}

TEST(BvhLayout, NodesMirrorTheBinaryTree) {
  test::Mesh mesh = test::randomSoup(5000, 0.05f, 21);
  Bvh2 bvh = buildBinnedSah(mesh.positions, mesh.triangles, {});
  GpuBvh gpu = toGpuLayout(bvh, mesh.positions, mesh.triangles);
  EXPECT_EQ(gpu.report.nodeCount, bvh.report.nodeCount);
  expectSlotsHoldPrimIndex(gpu, bvh, mesh);
  // One GPU node per inner node; walk both trees together.
  ASSERT_EQ(gpu.nodes.size(), bvh.nodes.size() - bvh.report.leafCount);
  std::vector<uint8_t> slotSeen(bvh.primIndex.size(), 0), gpuSeen(gpu.nodes.size(), 0);
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0, 0}};  // (bvh2 inner node, gpu node)
  while (!stack.empty()) {
    auto [b, g] = stack.back();
    stack.pop_back();
    ASSERT_LT(g, gpu.nodes.size());
    ASSERT_EQ(gpuSeen[g]++, 0);
    const GpuBvhNode& node = gpu.nodes[g];
    for (int k = 0; k < 2; ++k) {
      const Bvh2Node& child = bvh.nodes[bvh.nodes[b].leftFirst + k];
      EXPECT_EQ(childLo(node, k), child.lo);
      EXPECT_EQ(childHi(node, k), child.hi);
      const uint32_t ref = node.link[k], count = node.link[2 + k];
      if (child.isLeaf()) {
        EXPECT_EQ(count, child.triCount);
        EXPECT_EQ(ref, child.leftFirst);
        for (uint32_t s = ref; s < ref + count; ++s) ASSERT_EQ(slotSeen[s]++, 0);
      } else {
        EXPECT_EQ(count, 0u);
        stack.push_back({bvh.nodes[b].leftFirst + k, ref});
      }
    }
  }
  for (uint8_t s : slotSeen) ASSERT_EQ(s, 1);
  for (uint8_t s : gpuSeen) ASSERT_EQ(s, 1);
}

TEST(BvhLayout, SingleLeafTreeHasEmptySecondChild) {
  // Three triangles with the same box: a split costs SA + SA*1 + SA*2 > SA*3, so SAH keeps one leaf.
  test::Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
  mesh.triangles = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};
  Bvh2 bvh = buildBinnedSah(mesh.positions, mesh.triangles, {});
  ASSERT_EQ(bvh.nodes.size(), 1u);
  GpuBvh gpu = toGpuLayout(bvh, mesh.positions, mesh.triangles);
  ASSERT_EQ(gpu.nodes.size(), 1u);
  const GpuBvhNode& root = gpu.nodes[0];
  EXPECT_EQ(root.link, glm::uvec4(0, 0, 3, 0));
  EXPECT_EQ(childLo(root, 0), bvh.nodes[0].lo);
  EXPECT_EQ(childHi(root, 0), bvh.nodes[0].hi);
  EXPECT_TRUE(isEmptyChild(root, 1));
  expectSlotsHoldPrimIndex(gpu, bvh, mesh);
}

TEST(BvhLayout, EmptyTreeHasRootWithTwoEmptyChildren) {
  test::Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 1, 1}};
  mesh.triangles = {{0, 1, 1}};  // degenerate: dropped
  GpuBvh gpu = buildGpuBvh(mesh.positions, mesh.triangles, {});
  ASSERT_EQ(gpu.nodes.size(), 1u);
  EXPECT_TRUE(gpu.triangles.empty());
  EXPECT_TRUE(isEmptyChild(gpu.nodes[0], 0));
  EXPECT_TRUE(isEmptyChild(gpu.nodes[0], 1));
  EXPECT_EQ(gpu.nodes[0].link, glm::uvec4(0));
  EXPECT_EQ(gpu.report.trianglesDropped, 1u);
}

TEST(BvhLayout, RejectsTreeThatDoesNotMatchTheMesh) {
  test::Mesh mesh = test::randomSoup(100, 0.1f, 8);
  Bvh2 bvh = buildBinnedSah(mesh.positions, mesh.triangles, {});
  test::Mesh smaller = mesh;
  smaller.triangles.resize(50);
  EXPECT_THROW(toGpuLayout(bvh, smaller.positions, smaller.triangles), SceneError);
  Bvh2 broken = bvh;
  broken.nodes[0].leftFirst = static_cast<uint32_t>(broken.nodes.size());  // children out of range
  EXPECT_THROW(toGpuLayout(broken, mesh.positions, mesh.triangles), SceneError);
  Bvh2 bigLeaf = bvh;
  bigLeaf.nodes.resize(1);
  bigLeaf.nodes[0].leftFirst = 0;
  bigLeaf.nodes[0].triCount = 100;  // > HT_MAX_LEAF_SIZE
  EXPECT_THROW(toGpuLayout(bigLeaf, mesh.positions, mesh.triangles), SceneError);
}

}  // namespace
}  // namespace ht::bvh
