// bvh_builder.cpp - binned SAH build (see bvh_builder.h).
//
// Per node: bounds pass, binned SAH split search (binned_sah.h), leaf decision, partition, recursion.
// Leaf rule (C_trav = C_int = 1, tinybvh; docs/BVH.md §8.2): a node with n <= maxLeafSize triangles becomes a
// leaf when its leaf cost n*SA(node) does not exceed the best split cost SA(node) + SA(L)*n(L) + SA(R)*n(R);
// larger nodes are always split (maxLeafSize is a hard limit, so the packed GPU leaf count stays small).
// Depth bound: a subtree at depth d can hold at most maxLeafSize * 2^(maxDepth - d) triangles. When the SAH
// split would give a child more than its capacity, the node is split at the centroid median instead, which
// halves the count and therefore always fits. The root check (n <= maxLeafSize * 2^maxDepth) then
// guarantees every leaf lies at depth <= maxDepth (with maxDepth = 64 that holds for any 32-bit count).
// Parallelism: above kParallelMinPrims triangles, while the task budget lasts, the left subtree is built by
// a new thread into its own node vector and spliced in after the join, so the node order is deterministic
// (identical for any thread count).
#include "bvh/bvh_builder.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <thread>

#include "bvh/binned_sah.h"
#include "bvh/build_primitives.h"
#include "common/error.h"

namespace ht::bvh {
namespace {

constexpr uint32_t kParallelMinPrims = 4096;
constexpr uint32_t kMaxBins = 256;
constexpr uint32_t kMaxLeafSize = 16;  // HT_MAX_LEAF_SIZE of bvh_traversal.h
constexpr uint32_t kMaxDepth = 64;     // HT_BVH_MAX_DEPTH of gpu_node.h
constexpr uint32_t kMaxThreads = 64;

// Most triangles a subtree with `levels` levels below its root can hold.
uint64_t leafCapacity(uint32_t maxLeafSize, uint32_t levels) {
  return levels >= 40 ? UINT64_MAX : uint64_t{maxLeafSize} << levels;
}

void requireInRange(const char* field, uint32_t value, uint32_t lo, uint32_t hi) {
  if (value < lo || value > hi) {
    throw ConfigError("BuildOptions", field, std::to_string(value),
                      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
}

void validateOptions(const BuildOptions& options) {
  requireInRange("bins", options.bins, 2, kMaxBins);
  requireInRange("maxLeafSize", options.maxLeafSize, 1, kMaxLeafSize);
  requireInRange("maxDepth", options.maxDepth, 1, kMaxDepth);
}

// Number of subtree tasks: with several threads, 4 tasks per thread so that uneven top-level splits still
// keep every core busy (the OS balances the task threads); 1 means a serial build.
uint32_t resolveTaskBudget(uint32_t requested) {
  uint32_t threads = std::clamp(requested != 0 ? requested : std::thread::hardware_concurrency(), 1u, kMaxThreads);
  return threads == 1 ? 1 : 4 * threads;
}

// Appends the nodes of a separately built subtree (root at sub[0]) and stores its root at nodes[slot].
void spliceSubtree(std::vector<Bvh2Node>& nodes, uint32_t slot, const std::vector<Bvh2Node>& sub) {
  const uint32_t base = static_cast<uint32_t>(nodes.size());  // sub[j], j >= 1, lands at base + j - 1
  auto relocate = [base](Bvh2Node node) {
    if (!node.isLeaf()) node.leftFirst = base + node.leftFirst - 1;
    return node;
  };
  nodes[slot] = relocate(sub[0]);
  for (size_t j = 1; j < sub.size(); ++j) nodes.push_back(relocate(sub[j]));
}

class SubtreeBuilder {
 public:
  SubtreeBuilder(const BuildPrimitives& prims, const BuildOptions& options, std::vector<uint32_t>& primIndex)
      : prims_(prims), options_(options), primIndex_(primIndex), binner_(options.bins) {}

  // Builds the subtree of primIndex[begin, end) with its root at nodes[nodeIdx] (depth `depth`).
  void build(std::vector<Bvh2Node>& nodes, uint32_t nodeIdx, uint32_t begin, uint32_t end, uint32_t depth,
             uint32_t tasks) {
    std::span<uint32_t> ids(primIndex_.data() + begin, end - begin);
    const uint32_t n = end - begin;
    NodeBounds bounds = computeNodeBounds(prims_, ids);
    nodes[nodeIdx].lo = bounds.box.lo;
    nodes[nodeIdx].hi = bounds.box.hi;

    const uint32_t levelsLeft = options_.maxDepth - depth;
    if (n == 1 || levelsLeft == 0) return makeLeaf(nodes[nodeIdx], begin, n);
    SahSplit split = binner_.findBestSplit(prims_, ids, bounds.centroidBox);
    const float nodeArea = bounds.box.halfArea();
    if (n <= options_.maxLeafSize && (split.axis < 0 || static_cast<float>(n) * nodeArea <= nodeArea + split.cost)) {
      return makeLeaf(nodes[nodeIdx], begin, n);
    }

    const uint64_t childCapacity = leafCapacity(options_.maxLeafSize, levelsLeft - 1);
    const bool sahFits = split.axis >= 0 && split.leftCount <= childCapacity && n - split.leftCount <= childCapacity;
    const uint32_t leftN = sahFits ? binner_.partition(prims_, ids, bounds.centroidBox, split)
                                   : medianSplit(prims_, ids, bounds.centroidBox);

    const uint32_t left = static_cast<uint32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[nodeIdx].leftFirst = left;
    nodes[nodeIdx].triCount = 0;
    if (tasks > 1 && n >= kParallelMinPrims) {
      buildChildrenInParallel(nodes, left, begin, begin + leftN, end, depth + 1, tasks);
    } else {
      build(nodes, left, begin, begin + leftN, depth + 1, tasks);
      build(nodes, left + 1, begin + leftN, end, depth + 1, tasks);
    }
  }

 private:
  static void makeLeaf(Bvh2Node& node, uint32_t begin, uint32_t n) {
    node.leftFirst = begin;
    node.triCount = n;
  }

  void buildChildrenInParallel(std::vector<Bvh2Node>& nodes, uint32_t left, uint32_t begin, uint32_t mid, uint32_t end,
                               uint32_t depth, uint32_t tasks) {
    const uint32_t leftTasks = tasks / 2;
    std::vector<Bvh2Node> leftNodes(1), rightNodes(1);
    auto leftTask = std::async(std::launch::async, [&] {
      SubtreeBuilder sub(prims_, options_, primIndex_);
      leftNodes.reserve(2 * size_t{mid - begin});
      sub.build(leftNodes, 0, begin, mid, depth, leftTasks);
    });
    rightNodes.reserve(2 * size_t{end - mid});
    build(rightNodes, 0, mid, end, depth, tasks - leftTasks);
    leftTask.get();
    spliceSubtree(nodes, left, leftNodes);
    spliceSubtree(nodes, left + 1, rightNodes);
  }

  const BuildPrimitives& prims_;
  const BuildOptions& options_;
  std::vector<uint32_t>& primIndex_;
  SahBinner binner_;
};

void fillTreeStatistics(const Bvh2& bvh, BuildReport& report) {
  report.nodeCount = static_cast<uint32_t>(bvh.nodes.size());
  report.leafCount = 0;
  report.maxDepth = 0;
  if (bvh.nodes.empty()) return;
  struct Entry {
    uint32_t node, depth;
  };
  std::vector<Entry> stack{{0, 0}};
  while (!stack.empty()) {
    Entry e = stack.back();
    stack.pop_back();
    const Bvh2Node& node = bvh.nodes[e.node];
    if (node.isLeaf()) {
      ++report.leafCount;
      report.maxDepth = std::max(report.maxDepth, e.depth);
    } else {
      stack.push_back({node.leftFirst, e.depth + 1});
      stack.push_back({node.leftFirst + 1, e.depth + 1});
    }
  }
  report.avgLeafSize = static_cast<double>(bvh.primIndex.size()) / report.leafCount;
  report.sahCost = sahCost(bvh);
}

}  // namespace

double sahCost(const Bvh2& bvh) {
  if (bvh.nodes.empty()) return 0.0;
  auto area = [](const Bvh2Node& n) {
    Aabb box{n.lo, n.hi};
    return static_cast<double>(box.halfArea());
  };
  double sum = 0.0;
  for (const Bvh2Node& node : bvh.nodes) sum += node.isLeaf() ? area(node) * node.triCount : area(node);
  double rootArea = area(bvh.nodes[0]);
  // Kept triangles have non-zero area, so the root's half area is positive; guard anyway.
  return rootArea > 0.0 ? sum / rootArea : 0.0;
}

std::string BuildReport::summary() const {
  char line[256];
  std::snprintf(line, sizeof line,
                "bvh: %llu triangles in, %llu dropped; %u nodes, %u leaves (avg %.2f tris), depth %u, SAH %.3f, "
                "%.2f ms",
                static_cast<unsigned long long>(trianglesIn), static_cast<unsigned long long>(trianglesDropped),
                nodeCount, leafCount, avgLeafSize, maxDepth, sahCost, buildMs);
  return line;
}

Bvh2 buildBinnedSah(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                    const BuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  validateOptions(options);
  BuildPrimitives prims = prepareBuildPrimitives(positions, triangles);

  Bvh2 bvh;
  bvh.report.trianglesIn = triangles.size();
  bvh.report.trianglesDropped = prims.dropped;
  const uint64_t kept = prims.kept.size();
  if (kept > leafCapacity(options.maxLeafSize, options.maxDepth)) {
    throw ConfigError("BuildOptions", "maxDepth", std::to_string(options.maxDepth),
                      "too small for " + std::to_string(kept) + " triangles with maxLeafSize " +
                          std::to_string(options.maxLeafSize) + " (use the default 64)");
  }
  bvh.primIndex = std::move(prims.kept);
  if (kept > 0) {
    bvh.nodes.reserve(2 * kept);
    bvh.nodes.resize(1);
    SubtreeBuilder builder(prims, options, bvh.primIndex);
    builder.build(bvh.nodes, 0, 0, static_cast<uint32_t>(kept), 0, resolveTaskBudget(options.threads));
  }
  fillTreeStatistics(bvh, bvh.report);
  bvh.report.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace ht::bvh
