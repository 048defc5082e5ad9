// bvh_layout_choice.h - per scene: trace the single flattened BVH or the two-level BVH (docs/BVH.md §9.4).
//
// A second BVH level costs traversal work wherever instance boxes overlap (Benthin et al., HPG 2017: plain two-level
// BVHs up to about 2x slower than re-braided ones), and it only pays when nodes move. Rule: a scene with moved nodes
// uses the two-level BVH (a move then costs a refit and a top-level rebuild instead of a full rebuild); a static
// scene keeps the flattened BVH unless the two-level one is measured cheaper per ray. The measure is the mean
// traversal step count (node visits + triangle tests) over a fixed probe ray set: deterministic, so the choice does
// not flip with machine load, and it tracks trace time (holotrace-bench-bvh2 prints both, docs/BENCHMARKS.md).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "bvh/aabb.h"
#include "bvh/cpu_traversal.h"
#include "bvh/gpu_layout.h"
#include "bvh/two_level_bvh.h"

namespace ht::bvh {

enum class BvhLayout { Flattened, TwoLevel };

const char* bvhLayoutName(BvhLayout layout);

struct LayoutCosts {
  double flattenedStepsPerRay = 0.0;
  double twoLevelStepsPerRay = 0.0;
};

// `count` rays from points on the sphere around `bounds` (radius 1.5x its half diagonal) towards points inside it,
// from a fixed hash sequence: the same rays for the same bounds on every machine.
std::vector<gpu_shared::HtRay> layoutProbeRays(const Aabb& bounds, uint32_t count = 4096);

LayoutCosts measureLayoutCosts(const GpuBvh& flattened, const TwoLevelBvh& twoLevel,
                               std::span<const gpu_shared::HtRay> probeRays);

// nodesMoved: the scene had a node moved since it was loaded (or the caller expects moves).
BvhLayout chooseBvhLayout(bool nodesMoved, const LayoutCosts& costs);

}  // namespace ht::bvh
