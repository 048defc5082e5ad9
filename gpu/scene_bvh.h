// scene_bvh.h - the BVH a scene is traced with, in the layout chosen for it: the single flattened BVH or the
// two-level BVH over the scene's instances (docs/BVH.md §9.4, docs/REUSE.md §3). Built on the host, possibly off the
// thread that owns the device; the Renderer uploads it (gpu_scene.h).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "bvh/bvh_layout_choice.h"
#include "bvh/gpu_layout.h"
#include "bvh/two_level_bvh.h"
#include "scene/scene.h"

namespace ht::gpu {

// Automatic: a scene of one instance keeps the flattened BVH (the two-level one is the same tree plus a top node);
// otherwise both are built and chooseBvhLayout picks the one measured cheaper per ray (static scene).
// TwoLevel: a scene whose nodes move (holotraced after UpdateScene moved a node). Flattened: always the single tree.
enum class BvhLayoutPolicy { Automatic, Flattened, TwoLevel };

struct SceneBvh {
  bvh::BvhLayout layout = bvh::BvhLayout::Flattened;
  bvh::GpuBvh flattened;                       // layout Flattened
  std::unique_ptr<bvh::TwoLevelBvh> twoLevel;  // layout TwoLevel
  bool costsMeasured = false;                  // Automatic over several instances: costs holds both measures
  bvh::LayoutCosts costs;
  bvh::BuildReport report;  // of the layout kept (two-level: nodes of both levels, wall time of its build)
};

// The scene's instances (Scene::instances()) as two-level BVH ranges; instance i of the TwoLevelBvh is entry i.
std::vector<bvh::InstanceRange> instanceRanges(const Scene& scene);

SceneBvh buildSceneBvh(const Scene& scene, const bvh::BuildOptions& options, BvhLayoutPolicy policy);

// A flattened BVH built beforehand (bvh::buildGpuBvh).
SceneBvh flattenedSceneBvh(bvh::GpuBvh bvh);

}  // namespace ht::gpu
