// ray_types.h - ray and hit records shared by C++ and GLSL (std430 layout: 32 B and 16 B).
#ifndef HT_RAY_TYPES_H
#define HT_RAY_TYPES_H
#include "common/glsl_cpp.h"

HT_SHARED_BEGIN

struct HtRay {
  vec3 origin;
  float tmin;
  vec3 dir;  // need not be unit length; t is measured in units of |dir|
  float tmax;
};

HT_CONST uint HT_MISS = 0xFFFFFFFFu;

struct HtHit {
  float t;     // hit distance along dir; tmax of the ray on a miss
  uint triId;  // original (scene) triangle index, HT_MISS on a miss
  float u, v;  // barycentrics of vertices 1 and 2 (w0 = 1-u-v)
};

HT_SHARED_END
#endif
