#version 460
#extension GL_GOOGLE_include_directive : require
// raygen: one invocation per path (target x sample; listed target x sample while refining). Writes the primary ray
// of path i into entry i of ray queue 0; the depth-0 kernels know its radiance 0 and throughput 1 (common.glsl
// queue_path). Targets count pixels x, then rows y (from the bottom, docs/OPTICS.md §0), then views; subpixel models
// (lenticular, integral) have 3 targets per pixel (target = 3*pixel + c).
// The MODEL specialisation constant removes every other model's code.
#include "gpu/shaders/common.glsl"
#include "camera_models/footprint_sampling.h"
#include "camera_models/capture_grid_model.h"
#include "camera_models/integral_model.h"
layout(constant_id = HT_SPEC_MODEL) const uint MODEL = HT_MODEL_LENTICULAR;
// The lenticular panel's Gen3 cell layout, folded into the code (lenticular_model.h HT_LENTICULAR_CELL_MODE).
layout(constant_id = 1) const int LENTICULAR_CELL_MODE = 0;
layout(constant_id = 2) const int LENTICULAR_CELL_COUNT = 0;
// The refinement pass's pipeline (paths of listed targets): the base pass then has no list load to run masked.
layout(constant_id = 3) const bool REFINING = false;
// Progressive accumulation (gpu/accumulator.h): sample s of a target is index (its samples so far + s) of one
// sequence, with no spp-1 / spp-2 special case (docs/REUSE.md §1, §6 item 1).
layout(constant_id = 4) const bool PROGRESSIVE = false;
// A partial re-render with the primary rays cached (docs/REUSE.md §4): a listed target's rays are the frame's own,
// so they are copied from the cache rather than generated again (lenticular and projector rays cost more than a
// copy).
layout(constant_id = 5) const bool FROM_CACHE = false;
#define HT_LENTICULAR_CELL_MODE(p) LENTICULAR_CELL_MODE
#define HT_LENTICULAR_CELL_COUNT(p) LENTICULAR_CELL_COUNT
#include "camera_models/lenticular_model.h"
#include "camera_models/oblique_model.h"
#include "camera_models/pinhole_model.h"
#include "camera_models/projector_model.h"
#include "camera_models/quilt_model.h"
#define HT_RAY_TABLE_ORIGIN(i) texelFetch(rayTableTexels, int(2u * (i))).xyz
#define HT_RAY_TABLE_DIRECTION(i) texelFetch(rayTableTexels, int(2u * (i) + 1u)).xyz
#include "camera_models/ray_table_model.h"
#include "gpu/segment_cells.h"
#include "gpu/shaders/reuse_cache.glsl"

// Projector `view` assembled from single uniform members (projector_model.h ProjectorView: no 8 KiB copy).
ProjectorView frame_projector(uint view) {
  return ProjectorView(FRAME.camera.projectors.observer, FRAME.camera.projectors.scale, FRAME.camera.projectors.localToWorld,
                       FRAME.camera.projectors.projector[view], FRAME.camera.projectors.lens, FRAME.camera.projectors.distortion);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i == 0u) {
    COUNTERS.queueCount[0] = pc.batchCount;
    COUNTERS.queueCount[1] = 0u;
    COUNTERS.shadowCount = 0u;
  }
  if (i >= pc.batchCount) return;
  uint spp = FRAME.dims.z;
  uint width = FRAME.dims.x;
  uint height = FRAME.dims.y;
  uint path = pc.batchFirst + i;
  // While refined targets are traced (adaptive_refinement.h), path p is sample p % spp of the (p / spp)-th listed
  // target; its samples are those of a frame rendered at this spp.
  uint target = REFINING ? UintRef(FRAME.refine).v[FRAME.refineInfo.y + path / spp] : path / spp;
  uint s = path % spp;
  if (FROM_CACHE) {
    store_ray(0u, i, cached_primary_ray(target * spp + s));
    return;
  }
  uint perPixel = ht_model_has_subpixel_targets(MODEL) ? 3u : 1u;
  uint pixel = target / perPixel;
  uint c = target % perPixel;
  uint x = pixel % width;
  uint y = FRAME.views.w + (pixel / width) % height;  // the row in the whole view (the chunk may be a band of rows)
  uint view = FRAME.views.y + pixel / (width * height);
  // Decorrelation uses the target's index over the whole frame (all views, all rows), not within this chunk.
  uint globalTarget = frame_global_target(target);
  uint sampleIndex = PROGRESSIVE ? accum_samples_so_far(globalTarget) + s : s;
  vec2 xi = PROGRESSIVE ? footprint_sample_progressive(globalTarget, sampleIndex, FRAME.frame.x, FRAME.views.z)
                        : footprint_sample(globalTarget, s, spp, FRAME.frame.x, FRAME.views.z);
  vec3 origin;
  vec3 dir;
  if (MODEL == HT_MODEL_LENTICULAR) {
    lenticular_ray(FRAME.camera.lenticular, x, y, c, xi, origin, dir);
  } else if (MODEL == HT_MODEL_PINHOLE) {
    pinhole_ray(FRAME.camera.pinhole, x, y, xi, origin, dir);
  } else if (MODEL == HT_MODEL_QUILT) {
    quilt_ray(FRAME.camera.quilt, x, y, view, xi, origin, dir);
  } else if (MODEL == HT_MODEL_PROJECTOR_ARRAY) {
    if ((PROGRESSIVE || spp > 1u) && FRAME.camera.projectors.observer.z > 0.0f) {
      vec2 xiAngle = footprint_sample_angle(globalTarget, sampleIndex, PROGRESSIVE ? 3u : spp, FRAME.frame.x);
      projector_view_scattered_ray(frame_projector(view), x, y, xi, xiAngle, origin, dir);
    } else {
      projector_view_ray(frame_projector(view), x, y, xi, origin, dir);
    }
  } else if (MODEL == HT_MODEL_INTEGRAL) {
    integral_ray(FRAME.camera.integral, x, y, c, xi, origin, dir);
  } else if (MODEL == HT_MODEL_CAPTURE_GRID) {
    capture_grid_ray(FRAME.camera.captureGrid, x, y, view, xi, origin, dir);
  } else if (MODEL == HT_MODEL_OBLIQUE) {
    oblique_ray(FRAME.camera.oblique, x, y, view, xi, origin, dir);
  } else {
    ray_table_ray(FRAME.camera.rayTable, x, y, xi, origin, dir);
  }
  store_ray(0u, i, HtRay(origin, 0.0f, dir, 3.0e38f));  // path i = queue entry i, radiance 0, throughput 1 (queue_path)
}
