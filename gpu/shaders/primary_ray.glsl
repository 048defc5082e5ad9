// primary_ray.glsl - the primary ray of one sample of one target (docs/OPTICS.md, every display model), the one
// source raygen.comp generates rays from and the accumulations' marking pass regenerates them from
// (mark_accumulated.comp), so both see the same ray. Included after common.glsl; declares specialisation constants
// 0-2: the camera model (HT_SPEC_MODEL, which removes every other model's code) and a lenticular panel's Gen3 cell
// layout, folded into the code (lenticular_model.h HT_LENTICULAR_CELL_MODE).
// Targets count pixels x, then rows y (from the bottom, docs/OPTICS.md §0), then views; subpixel models
// (lenticular, integral) have 3 targets per pixel (target = 3*pixel + c).
#include "camera_models/footprint_sampling.h"
#include "camera_models/capture_grid_model.h"
#include "camera_models/integral_model.h"
layout(constant_id = HT_SPEC_MODEL) const uint MODEL = HT_MODEL_LENTICULAR;
layout(constant_id = 1) const int LENTICULAR_CELL_MODE = 0;
layout(constant_id = 2) const int LENTICULAR_CELL_COUNT = 0;
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

// Projector `view` assembled from single uniform members (projector_model.h ProjectorView: no 8 KiB copy).
ProjectorView frame_projector(uint view) {
  return ProjectorView(FRAME.camera.projectors.observer, FRAME.camera.projectors.scale, FRAME.camera.projectors.localToWorld,
                       FRAME.camera.projectors.projector[view], FRAME.camera.projectors.lens, FRAME.camera.projectors.distortion);
}

// The primary ray of chunk target `target`, sample index `sampleIndex`. `progressive`: the sample is index
// `sampleIndex` of the target's one sequence (footprint_sample_progressive, no spp-1 / spp-2 special case:
// docs/REUSE.md §1, §6 item 1); otherwise sample `sampleIndex` of `spp` (footprint_sample).
HtRay primary_ray(uint target, uint sampleIndex, uint spp, bool progressive) {
  uint width = FRAME.dims.x;
  uint height = FRAME.dims.y;
  uint perPixel = ht_model_has_subpixel_targets(MODEL) ? 3u : 1u;
  uint pixel = target / perPixel;
  uint c = target % perPixel;
  uint x = pixel % width;
  uint y = FRAME.views.w + (pixel / width) % height;  // the row in the whole view (the chunk may be a band of rows)
  uint view = FRAME.views.y + pixel / (width * height);
  // Decorrelation uses the target's index over the whole frame (all views, all rows), not within this chunk.
  uint globalTarget = frame_global_target(target);
  vec2 xi = progressive ? footprint_sample_progressive(globalTarget, sampleIndex, FRAME.frame.x, FRAME.views.z)
                        : footprint_sample(globalTarget, sampleIndex, spp, FRAME.frame.x, FRAME.views.z);
  vec3 origin;
  vec3 dir;
  if (MODEL == HT_MODEL_LENTICULAR) {
    lenticular_ray(FRAME.camera.lenticular, x, y, c, xi, origin, dir);
  } else if (MODEL == HT_MODEL_PINHOLE) {
    pinhole_ray(FRAME.camera.pinhole, x, y, xi, origin, dir);
  } else if (MODEL == HT_MODEL_QUILT) {
    quilt_ray(FRAME.camera.quilt, x, y, view, xi, origin, dir);
  } else if (MODEL == HT_MODEL_PROJECTOR_ARRAY) {
    if ((progressive || spp > 1u) && FRAME.camera.projectors.observer.z > 0.0f) {
      vec2 xiAngle = footprint_sample_angle(globalTarget, sampleIndex, progressive ? 3u : spp, FRAME.frame.x);
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
  return HtRay(origin, 0.0f, dir, 3.0e38f);
}
