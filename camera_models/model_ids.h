// model_ids.h - the camera-model numbers, one source for C++ and GLSL: the index of a model's row in the display-model
// registry (display_model_registry.h), the C++ enum DisplayModel, the alternative of FrameCamera (frame_camera.h) and
// the MODEL specialisation constant of the raygen / resolve / refine_select kernels. GLSL sees no C++ enum, so the
// numbers live here and DisplayModel takes its values from them.
#ifndef HT_MODEL_IDS_H
#define HT_MODEL_IDS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

// Subpixel models (lenticular, integral) trace each R, G, B subpixel with its own rays and keep one channel per
// target; the others trace RGB pixels of `views` images.
HT_CONST uint HT_MODEL_LENTICULAR = 0u;
HT_CONST uint HT_MODEL_PINHOLE = 1u;
HT_CONST uint HT_MODEL_QUILT = 2u;  // a lenticular display's quilt cameras (not a config "model")
HT_CONST uint HT_MODEL_PROJECTOR_ARRAY = 3u;
HT_CONST uint HT_MODEL_INTEGRAL = 4u;
HT_CONST uint HT_MODEL_CAPTURE_GRID = 5u;
HT_CONST uint HT_MODEL_OBLIQUE = 6u;
HT_CONST uint HT_MODEL_RAY_TABLE = 7u;
HT_CONST uint HT_MODEL_COUNT = 8u;

HT_INLINE bool ht_model_has_subpixel_targets(uint model) {
  return model == HT_MODEL_LENTICULAR || model == HT_MODEL_INTEGRAL;
}

HT_SHARED_END
#endif  // HT_MODEL_IDS_H
