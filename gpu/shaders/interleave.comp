#version 460
#extension GL_GOOGLE_include_directive : require
// interleave: packs the resolved subpixels into RGB pixels, view by view, flipping rows so that row 0 of each
// output view is its top (targets count y from the bottom, docs/OPTICS.md §0). The view phase of each subpixel, incl. BGR
// panels (flipSubp) and Gen3 cells, was already applied when its rays were generated.
#include "gpu/shaders/common.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint width = FRAME.dims.x;
  uint height = FRAME.dims.y;
  uint viewPixels = width * height;
  if (i >= viewPixels * FRAME.views.x) return;
  uint view = i / viewPixels;
  uint inView = i % viewPixels;
  uint row = inView / width;
  uint x = inView % width;
  uint pixel = view * viewPixels + (height - 1u - row) * width + x;
  int k = int(3u * pixel);
  vec4 rgb = vec4(imageLoad(subpixelBuffer, k).x, imageLoad(subpixelBuffer, k + 1).x, imageLoad(subpixelBuffer, k + 2).x, 1.0f);
  imageStore(outputImage, int(i), rgb);
}
