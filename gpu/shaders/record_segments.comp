#version 460
#extension GL_GOOGLE_include_directive : require
// record_segments: for frames that keep reuse state (gpu/frame_reuse.h, docs/REUSE.md §4), one invocation per entry
// of the current ray queue, after this depth's closest-hit trace and shadow trace and before gather_direct clears
// the shadow slots: ORs the world-grid cells of the entry's segment (to its hit; a miss to infinity) and of every
// shadow ray its path emitted at this depth (to the light) into the mask of the path's target (gpu/segment_cells.h).
#include "gpu/shaders/common.glsl"
#include "gpu/segment_cells.h"

layout(constant_id = 0) const bool LISTED = false;  // paths of listed targets (a partial re-render)

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= COUNTERS.queueCount[pc.queue]) return;
  uint path = queue_path(i);
  uint entry = (pc.batchFirst + path) / FRAME.dims.z;
  uint target = LISTED ? UintRef(FRAME.refine).v[FRAME.refineInfo.y + entry] : entry;
  HtRay ray = load_ray(pc.queue, i);
  HtHit hit = load_hit(i);
  uvec2 cells = ht_segment_cells(ray.origin, ray.dir, ray.tmin, hit.triId != HT_MISS ? hit.t : ray.tmax, FRAME.grid);
  uint lightCount = FRAME.scene.x;
  for (uint l = 0u; l < lightCount; ++l) {
    uint slot = path * lightCount + l;
    if (imageLoad(shadowContribBuffer, int(slot)).w != 0.0f) {  // live: emitted at this depth (occluded or not)
      HtRay shadow = load_shadow_ray(slot);
      cells |= ht_segment_cells(shadow.origin, shadow.dir, shadow.tmin, shadow.tmax, FRAME.grid);
    }
  }
  if (cells.x != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[2u * target], cells.x);
  if (cells.y != 0u) atomicOr(UintRef(FRAME.segmentMasks).v[2u * target + 1u], cells.y);
}
