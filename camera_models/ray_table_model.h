// ray_table_model.h - rays of a display calibrated per pixel (model "ray-table"), shared C++/GLSL.
//
// The table holds one ray (origin, unit direction) per pixel, index i = y*width + x, y from the bottom (docs/OPTICS.md
// §0); table entry (x, y) is the ray through the pixel's centre. A sample at footprint xi in [0,1)^2 of pixel (x, y)
// lies at table position (x + xi.x - 0.5, y + xi.y - 0.5), clamped to [0, width-1] x [0, height-1]; origin and
// direction are bilinearly interpolated between the four surrounding entries and the direction renormalised (normalised
// linear interpolation). At xi = (0.5, 0.5) (and wherever the clamped position is an entry) both weights are 0 and the
// entry is returned bit-exactly: no renormalisation then, the loader stores unit directions (RayTable).
//
// Table access goes through macros so that GLSL and C++ share this code (as bvh/bvh_traversal.h):
//   C++ : functions take `HT_RAY_TABLE_PARAM` = `const RayTableView& rayTable_,` first; HT_RAY_TABLE_ORIGIN(i) =
//         rayTable_.origins[i], HT_RAY_TABLE_DIRECTION(i) = rayTable_.directions[i] (vec3).
//   GLSL: HT_RAY_TABLE_PARAM / HT_RAY_TABLE_ARG are empty; the including shader defines HT_RAY_TABLE_ORIGIN(i) and
//         HT_RAY_TABLE_DIRECTION(i) (uint i -> vec3), e.g. texelFetch(originTexels, int(i)).xyz, before including.
#ifndef HT_RAY_TABLE_MODEL_H
#define HT_RAY_TABLE_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/ray_table_params.h"

#ifdef HT_GLSL
#if !defined(HT_RAY_TABLE_ORIGIN) || !defined(HT_RAY_TABLE_DIRECTION)
#error "define HT_RAY_TABLE_ORIGIN(i) and HT_RAY_TABLE_DIRECTION(i) before including camera_models/ray_table_model.h"
#endif
#define HT_RAY_TABLE_PARAM
#define HT_RAY_TABLE_ARG
#else
HT_SHARED_BEGIN
// Host view of the table (RayTable::origins / directions, width*height entries each).
struct RayTableView {
  const vec3* origins;
  const vec3* directions;
};
HT_SHARED_END
#define HT_RAY_TABLE_PARAM const RayTableView &rayTable_,
#define HT_RAY_TABLE_ARG rayTable_,
#ifndef HT_RAY_TABLE_ORIGIN
#define HT_RAY_TABLE_ORIGIN(i) rayTable_.origins[i]
#endif
#ifndef HT_RAY_TABLE_DIRECTION
#define HT_RAY_TABLE_DIRECTION(i) rayTable_.directions[i]
#endif
#endif

HT_SHARED_BEGIN

// Left neighbour index and weight of the right one for pixel coordinate c and footprint offset u = xi - 0.5 along an
// axis of n entries: position c + u clamped to [0, n-1]. The weight is computed from u, not from c + u, so it keeps
// full precision for large tables and is exactly 0 for u = 0.
HT_INLINE void ray_table_axis(int c, float u, int n, HT_OUT(int) i0, HT_OUT(float) w) {
  i0 = u < 0.0f ? c - 1 : c;
  w = u < 0.0f ? u + 1.0f : u;
  if (i0 < 0) {
    i0 = 0;
    w = 0.0f;
  }
  if (i0 >= n - 1) {
    i0 = n - 1;
    w = 0.0f;
  }
}

HT_INLINE vec3 ray_table_bilerp(vec3 a00, vec3 a10, vec3 a01, vec3 a11, float wx, float wy) {
  HT_PRECISE vec3 bottom = a00 * (1.0f - wx) + a10 * wx;
  HT_PRECISE vec3 top = a01 * (1.0f - wx) + a11 * wx;
  HT_PRECISE vec3 r = bottom * (1.0f - wy) + top * wy;
  return r;
}

// The interpolated ray in table units (before rayTable.units and the placement).
HT_INLINE void ray_table_local_ray(HT_RAY_TABLE_PARAM RayTableParams p, uint x, uint y, vec2 xi, HT_OUT(vec3) origin,
                                   HT_OUT(vec3) dir) {
  int x0, y0;
  float wx, wy;
  ray_table_axis(int(x), xi.x - 0.5f, p.size.x, x0, wx);
  ray_table_axis(int(y), xi.y - 0.5f, p.size.y, y0, wy);
  int x1 = min(x0 + 1, p.size.x - 1), y1 = min(y0 + 1, p.size.y - 1);
  uint w = uint(p.size.x);
  uint i00 = uint(y0) * w + uint(x0), i10 = uint(y0) * w + uint(x1);
  uint i01 = uint(y1) * w + uint(x0), i11 = uint(y1) * w + uint(x1);
  origin = ray_table_bilerp(HT_RAY_TABLE_ORIGIN(i00), HT_RAY_TABLE_ORIGIN(i10), HT_RAY_TABLE_ORIGIN(i01),
                            HT_RAY_TABLE_ORIGIN(i11), wx, wy);
  dir = ray_table_bilerp(HT_RAY_TABLE_DIRECTION(i00), HT_RAY_TABLE_DIRECTION(i10), HT_RAY_TABLE_DIRECTION(i01),
                         HT_RAY_TABLE_DIRECTION(i11), wx, wy);
  if (wx != 0.0f || wy != 0.0f) dir = normalize(dir);
}

// World ray: o_w = localToWorld * (units * o), d_w = mat3(localToWorld) * d (rotation-free, so still unit length).
HT_INLINE void ray_table_ray(HT_RAY_TABLE_PARAM RayTableParams p, uint x, uint y, vec2 xi, HT_OUT(vec3) origin,
                             HT_OUT(vec3) dir) {
  vec3 o, d;
  ray_table_local_ray(HT_RAY_TABLE_ARG p, x, y, xi, o, d);
  origin = vec3(p.localToWorld * vec4(o * p.scale.x, 1.0f));
  dir = mat3(p.localToWorld) * d;
}

HT_SHARED_END
#endif  // HT_RAY_TABLE_MODEL_H
