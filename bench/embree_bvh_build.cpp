// embree_bvh_build.cpp - see embree_bvh_build.h. Node callbacks follow Embree's tutorials/bvh_builder.
#include "bench/embree_bvh_build.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "common/error.h"

namespace ht::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Box {
  glm::vec3 lo, hi;
};

struct BuiltNode {  // allocated by Embree's thread-local allocator; lives until rtcReleaseBVH
  bool leaf = false;
  Box childBox[2]{};
  BuiltNode* child[2]{nullptr, nullptr};
  std::uint32_t primCount = 0;
  std::uint32_t prims[1];  // leaf: primCount entries (allocated past the struct)
};

void* createNode(RTCThreadLocalAllocator alloc, unsigned int, void*) {
  void* memory = rtcThreadLocalAlloc(alloc, sizeof(BuiltNode), 16);
  return new (memory) BuiltNode{};
}

void setNodeChildren(void* nodePtr, void** children, unsigned int count, void*) {
  auto* node = static_cast<BuiltNode*>(nodePtr);
  for (unsigned i = 0; i < count && i < 2; ++i) node->child[i] = static_cast<BuiltNode*>(children[i]);
}

void setNodeBounds(void* nodePtr, const RTCBounds** bounds, unsigned int count, void*) {
  auto* node = static_cast<BuiltNode*>(nodePtr);
  for (unsigned i = 0; i < count && i < 2; ++i) {
    node->childBox[i] = {{bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z},
                         {bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z}};
  }
}

void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  const std::size_t bytes = sizeof(BuiltNode) + count * sizeof(std::uint32_t);
  auto* node = new (rtcThreadLocalAlloc(alloc, bytes, 16)) BuiltNode{};
  node->leaf = true;
  node->primCount = std::uint32_t(count);
  for (std::size_t i = 0; i < count; ++i) node->prims[i] = prims[i].primID;
  return node;
}

std::vector<RTCBuildPrimitive> makePrimitives(std::span<const glm::vec3> positions,
                                              std::span<const glm::uvec3> triangles) {
  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const glm::vec3 a = positions[triangles[i].x], b = positions[triangles[i].y], c = positions[triangles[i].z];
    const glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    prims.push_back({lo.x, lo.y, lo.z, 0u, hi.x, hi.y, hi.z, std::uint32_t(i)});
  }
  return prims;
}

// Depth-first flattening into Bvh2: the children of an inner node occupy two adjacent slots.
void flatten(const BuiltNode* node, std::uint32_t slot, std::uint32_t depth, bvh::Bvh2& out) {
  if (node->leaf) {
    out.nodes[slot].leftFirst = std::uint32_t(out.primIndex.size());
    out.nodes[slot].triCount = node->primCount;
    out.primIndex.insert(out.primIndex.end(), node->prims, node->prims + node->primCount);
    out.report.leafCount++;
    out.report.maxDepth = std::max(out.report.maxDepth, depth);
    return;
  }
  const auto first = std::uint32_t(out.nodes.size());
  out.nodes.resize(out.nodes.size() + 2);
  out.nodes[slot].leftFirst = first;
  out.nodes[slot].triCount = 0;
  for (int k = 0; k < 2; ++k) {
    out.nodes[first + k].lo = node->childBox[k].lo;
    out.nodes[first + k].hi = node->childBox[k].hi;
    flatten(node->child[k], first + k, depth + 1, out);
  }
}

RTCBuildArguments buildArguments(RTCBVH bvh, std::vector<RTCBuildPrimitive>& prims, std::uint32_t maxLeafSize) {
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildFlags = RTC_BUILD_FLAG_NONE;
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = 2;
  args.maxDepth = 64;
  args.sahBlockSize = 1;
  args.minLeafSize = 1;
  args.maxLeafSize = maxLeafSize;
  args.traversalCost = 1.0f;
  args.intersectionCost = 1.0f;
  args.bvh = bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.capacity();
  args.createNode = createNode;
  args.setNodeChildren = setNodeChildren;
  args.setNodeBounds = setNodeBounds;
  args.createLeaf = createLeaf;
  return args;
}

}  // namespace

EmbreeBvhBuild buildEmbreeBvh(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                              std::uint32_t maxLeafSize) {
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device) throw Error("Embree: rtcNewDevice failed");
  RTCBVH bvh = rtcNewBVH(device);
  std::vector<RTCBuildPrimitive> prims = makePrimitives(positions, triangles);
  const RTCBuildArguments args = buildArguments(bvh, prims, maxLeafSize);
  EmbreeBvhBuild result;
  const auto start = Clock::now();
  const auto* root = static_cast<const BuiltNode*>(rtcBuildBVH(&args));
  result.buildMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE || !root) {
    rtcReleaseBVH(bvh);
    rtcReleaseDevice(device);
    throw Error("Embree: rtcBuildBVH failed with RTCError " + std::to_string(int(error)));
  }
  const auto convertStart = Clock::now();
  bvh::Bvh2& tree = result.tree;
  tree.nodes.resize(1);
  Box rootBox{glm::vec3(std::numeric_limits<float>::infinity()), glm::vec3(-std::numeric_limits<float>::infinity())};
  for (const auto& p : prims) {  // rtcBuildBVH may reorder prims; the union is the same
    rootBox.lo = glm::min(rootBox.lo, glm::vec3(p.lower_x, p.lower_y, p.lower_z));
    rootBox.hi = glm::max(rootBox.hi, glm::vec3(p.upper_x, p.upper_y, p.upper_z));
  }
  tree.nodes[0].lo = rootBox.lo;
  tree.nodes[0].hi = rootBox.hi;
  flatten(root, 0, 0, tree);
  tree.report.nodeCount = std::uint32_t(tree.nodes.size());
  tree.report.trianglesIn = triangles.size();
  tree.report.avgLeafSize = tree.report.leafCount ? double(tree.primIndex.size()) / tree.report.leafCount : 0.0;
  tree.report.sahCost = bvh::sahCost(tree);
  tree.report.buildMs = result.buildMs;
  result.convertMs = std::chrono::duration<double, std::milli>(Clock::now() - convertStart).count();
  rtcReleaseBVH(bvh);
  rtcReleaseDevice(device);
  return result;
}

}  // namespace ht::bench
