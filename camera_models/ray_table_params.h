// ray_table_params.h - GPU-visible parameter block of the generic per-pixel ray table (ray_table_model.h).
// std430-safe: only vec4/ivec4/mat4 members.
#ifndef HT_RAY_TABLE_PARAMS_H
#define HT_RAY_TABLE_PARAMS_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

struct RayTableParams {
  ivec4 size;         // x table width, y table height (entries = pixels), zw unused
  mat4 localToWorld;  // table frame (after scaling) -> world; rotation-free (translation to camera.target)
  vec4 scale;         // x world units per table unit (rayTable.units), yzw unused
};

HT_SHARED_END
#endif  // HT_RAY_TABLE_PARAMS_H
