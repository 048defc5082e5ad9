// camera_block.h - the camera parameters of a frame as the GPU kernels read them (member `camera` of the FrameBlock
// uniform, gpu/wavefront_types.h): one parameter block per model, of which a frame fills its own model's
// (display-model registry row writeBlock) and leaves the others zero. Shared by C++ and GLSL; every member is a
// 16-byte multiple of vec4/ivec4/mat4, so std140 and C++ agree on the layout.
#ifndef HT_CAMERA_BLOCK_H
#define HT_CAMERA_BLOCK_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"
#include "camera_models/capture_grid_params.h"
#include "camera_models/integral_params.h"
#include "camera_models/oblique_params.h"
#include "camera_models/projector_params.h"
#include "camera_models/quilt_params.h"
#include "camera_models/ray_table_params.h"

HT_SHARED_BEGIN

struct CameraBlock {
  LenticularParams lenticular;
  PinholeParams pinhole;
  QuiltParams quilt;
  IntegralParams integral;
  CaptureGridParams captureGrid;
  ObliqueParams oblique;
  RayTableParams rayTable;
  ProjectorArrayParams projectors;
};

HT_SHARED_END
#endif  // HT_CAMERA_BLOCK_H
