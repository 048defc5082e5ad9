#version 460
#extension GL_GOOGLE_include_directive : require
// interleave: packs the resolved subpixels into RGB pixels, view by view, flipping rows so that row 0 of each
// output view is its top (targets count y from the bottom, docs/OPTICS.md §0). The view phase of each subpixel, incl. BGR
// panels (flipSubp) and Gen3 cells, was already applied when its rays were generated.
#include "gpu/shaders/common.glsl"

layout(constant_id = HT_SPEC_MODEL) const uint MODEL = HT_MODEL_LENTICULAR;
// A partial re-render (docs/REUSE.md §4): one invocation per listed target (entries pc.batchFirst + i), packing the
// pixel it belongs to; the output image still holds the frame re-rendered in part, so no other pixel changes. The
// three subpixel targets of a pixel may all be listed: they store the same values.
layout(constant_id = 1) const bool LISTED = false;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint width = FRAME.dims.x;
  uint height = FRAME.dims.y;
  uint viewPixels = width * height;
  uint pixel;  // as the subpixel buffer counts them: rows from the bottom
  uint outIndex;
  if (LISTED) {
    if (i >= pc.batchCount) return;
    uint target = UintRef(FRAME.refine).v[FRAME.refineInfo.y + pc.batchFirst + i];
    pixel = ht_model_has_subpixel_targets(MODEL) ? target / 3u : target;
    uint inView = pixel % viewPixels;
    outIndex = pixel - inView + (height - 1u - inView / width) * width + inView % width;
  } else {
    if (i >= viewPixels * FRAME.views.x) return;
    uint view = i / viewPixels;
    uint inView = i % viewPixels;
    uint row = inView / width;
    uint x = inView % width;
    pixel = view * viewPixels + (height - 1u - row) * width + x;
    outIndex = i;
  }
  int k = int(3u * pixel);
  vec4 rgb = vec4(imageLoad(subpixelBuffer, k).x, imageLoad(subpixelBuffer, k + 1).x, imageLoad(subpixelBuffer, k + 2).x, 1.0f);
  imageStore(outputImage, int(outIndex), rgb);
}
