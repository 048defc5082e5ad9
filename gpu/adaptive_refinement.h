// adaptive_refinement.h - which targets of a frame get more samples (C++ and GLSL, one source).
//
// Contrast-driven refinement after Mitchell, "Generating antialiased images at low sampling densities",
// SIGGRAPH 1987: a first pass samples every target sparsely; where a value differs from its neighbours by more
// than a threshold the footprint likely holds an edge, a texture step or a parallax change, and only there are more
// samples spent. Here a target (a subpixel of a lenticular / integral panel, or an RGB pixel of the other models)
// is compared with the same channel(s) of its 4 neighbouring pixels in the same view. For a lenticular panel a
// horizontal neighbour is one pixel away in space and about 3 / (subpixels per lens) away in view phase, so the test
// covers the spatial and the angular extent of the subpixel's footprint (docs/OPTICS.md §1) at a slightly coarser
// scale: conservative. Values are compared sRGB-encoded and clamped to [0, 1], the scale the display shows and the
// quality benchmark measures (PSNR on sRGB): a fixed threshold means the same visible step in dark and bright areas.
//
// A target is refined when its contrast is >= the threshold, so threshold 0 refines every target (each then takes the
// mean of its base samples and the samples a frame at the refinement spp gives it, resolve.comp) and a threshold
// above 1 refines none.
#ifndef HT_ADAPTIVE_REFINEMENT_H
#define HT_ADAPTIVE_REFINEMENT_H
#include "common/glsl_cpp.h"
#include "common/srgb.h"

HT_SHARED_BEGIN

// Largest sRGB difference between `value` and the neighbour values (linear); absent neighbours pass the value
// itself. NaN values (never written by resolve, which zeroes them) would encode as 0.
HT_INLINE float ht_refine_contrast(float value, float left, float right, float below, float above) {
  float v = ht_srgb_encode(value);
  float d = max(abs(v - ht_srgb_encode(left)), abs(v - ht_srgb_encode(right)));
  return max(d, max(abs(v - ht_srgb_encode(below)), abs(v - ht_srgb_encode(above))));
}

HT_SHARED_END
#endif
