#version 460
#extension GL_GOOGLE_include_directive : require
// raygen: one invocation per path (target x sample; listed target x sample while refining). Writes the primary ray
// of path i (primary_ray.glsl) into entry i of ray queue 0; the depth-0 kernels know its radiance 0 and throughput
// 1 (common.glsl queue_path).
#include "gpu/shaders/common.glsl"
#include "gpu/shaders/primary_ray.glsl"  // constants 0-2: the model and the lenticular cell layout
// The refinement pass's pipeline (paths of listed targets): the base pass then has no list load to run masked.
layout(constant_id = 3) const bool REFINING = false;
// Progressive accumulation (gpu/accumulator.h): sample s of a target is index (its samples so far + s) of one
// sequence, with no spp-1 / spp-2 special case (docs/REUSE.md §1, §6 item 1).
layout(constant_id = 4) const bool PROGRESSIVE = false;
// A partial re-render with the primary rays cached (docs/REUSE.md §4): a listed target's rays are the frame's own,
// so they are copied from the cache rather than generated again (lenticular and projector rays cost more than a
// copy).
layout(constant_id = 5) const bool FROM_CACHE = false;
#include "gpu/segment_cells.h"
#include "gpu/shaders/reuse_cache.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i == 0u) {
    COUNTERS.queueCount[0] = pc.batchCount;
    COUNTERS.queueCount[1] = 0u;
    COUNTERS.shadowCount = 0u;
  }
  if (i >= pc.batchCount) return;
  uint spp = FRAME.dims.z;
  uint path = pc.batchFirst + i;
  // While refined targets are traced (adaptive_refinement.h), path p is sample p % spp of the (p / spp)-th listed
  // target; its samples are those of a frame rendered at this spp.
  uint target = REFINING ? UintRef(FRAME.refine).v[FRAME.refineInfo.y + path / spp] : path / spp;
  uint s = path % spp;
  if (FROM_CACHE) {
    store_ray(0u, i, cached_primary_ray(target * spp + s));
    return;
  }
  uint sampleIndex = PROGRESSIVE ? accum_samples_so_far(frame_global_target(target)) + s : s;
  store_ray(0u, i, primary_ray(target, sampleIndex, spp, PROGRESSIVE));  // path i = queue entry i (queue_path)
}
