// segment_cells.h - the conservative per-target summary of a frame's path segments that partial re-render tests
// against a moved node (docs/REUSE.md §4), one source for the GLSL recording pass and its C++ reference.
//
// The world grid is 4 x 4 x 4 cells over the scene's bounds at load; the cells at the grid's faces reach to
// infinity, so every point of space lies in exactly one cell and nodes moved outside the load bounds still map to
// cells. A target's mask has one bit per cell (64 bits, two 32-bit words) for every cell any of its segments met:
// primary and secondary rays up to their hit (misses to infinity) and every shadow ray to its light. A segment can
// change after a node moves only if it meets the node's old or new bounds, so a target whose mask shares no cell
// with those bounds (padded by HT_GRID_PAD cells against float rounding) keeps its value bit for bit. Where the
// primary rays and hits are cached (gpu/frame_reuse.h), primary segments stay out of the mask and the marking pass
// tests them exactly against the padded bounds (ht_segment_meets_box): they are most of a display's segments and
// the ones the coarse grid over-invalidates most. The shadow rays of those primary hits go with them: their cells join
// the primary cells, and the marking pass tests the segments from each cached hit to each light exactly
// (ht_shadow_meets_box), so a shadow that only passes near the moved node's cells no longer re-traces a target.
#ifndef HT_SEGMENT_CELLS_H
#define HT_SEGMENT_CELLS_H
#include "common/glsl_cpp.h"
#ifdef HT_GLSL
#define HT_SEGMENT_NAN(x) isnan(x)
#else
#include <cmath>
#define HT_SEGMENT_NAN(x) std::isnan(x)
#endif

HT_SHARED_BEGIN

HT_CONST uint HT_GRID_CELLS = 4u;             // per axis: 64 cells, one bit each
HT_CONST float HT_GRID_PAD = 1.0f / 1024.0f;  // cells: pads moved bounds over the rounding of segment points
HT_CONST float HT_GRID_T_INFINITY = 3.4e38f;  // beyond any ray's tmax (3e38 for rays that run to infinity)
// Targets one invocation of the marking pass's per-target mode compares (mark_dirty.comp MARK_TARGETS): lavapipe
// pays much per invocation, and the comparison itself is a few instructions.
HT_CONST uint HT_MARK_TARGETS_PER_INVOCATION = 4u;
// Samples per target the accumulations' exact test (mark_accumulated.comp) generates again; a target with more
// restarts untested. lavapipe stops an invocation's loops after 65,535 iterations in all: this stays far below.
HT_CONST uint HT_MARK_MAX_SAMPLES = 1024u;

// The grid in the FrameBlock: cell coordinate = (p - origin) * scale, cells [0, 4) per axis.
struct SegmentGrid {
  vec4 origin;  // xyz: the scene's lower bounds corner
  vec4 scale;   // xyz: cells per world unit (4 / extent)
};

// The cell of cell coordinate c along one axis, the face cells reaching to +-infinity.
HT_INLINE uint ht_grid_cell(float c) { return uint(clamp(floor(c), 0.0f, float(HT_GRID_CELLS - 1u))); }

// The bits [a, b] of a 4-bit set (none when a > b).
HT_INLINE uint ht_grid_span(uint a, uint b) { return ((2u << b) - 1u) & ~((1u << a) - 1u); }

// The mask of the cells [a, b] (inclusive, per axis): bit (z * 4 + y) * 4 + x; word 0 holds layers z = 0, 1. Without
// loops (the recording pass builds one per piece of every segment): the row of x bits is copied to every row y of the
// span by a multiplication with the sum of 2^(4y), whose copies cannot overlap, and the layer to every z alike.
HT_INLINE uvec2 ht_grid_box_mask(uvec3 a, uvec3 b) {
  uint row = ht_grid_span(a.x, b.x), ys = ht_grid_span(a.y, b.y), zs = ht_grid_span(a.z, b.z);
  uint layer = row * ((ys & 1u) | ((ys & 2u) << 3u) | ((ys & 4u) << 6u) | ((ys & 8u) << 9u));
  return uvec2(layer * ((zs & 1u) | ((zs & 2u) << 15u)), layer * (((zs >> 2u) & 1u) | ((zs & 8u) << 13u)));
}

// The cells of the world box [lo, hi] padded by HT_GRID_PAD cells (the moved node's old or new bounds).
HT_INLINE uvec2 ht_grid_bounds_mask(vec3 lo, vec3 hi, SegmentGrid g) {
  vec3 origin = vec3(g.origin.x, g.origin.y, g.origin.z), scale = vec3(g.scale.x, g.scale.y, g.scale.z);
  vec3 a = (lo - origin) * scale - vec3(HT_GRID_PAD), b = (hi - origin) * scale + vec3(HT_GRID_PAD);
  return ht_grid_box_mask(uvec3(ht_grid_cell(a.x), ht_grid_cell(a.y), ht_grid_cell(a.z)),
                          uvec3(ht_grid_cell(b.x), ht_grid_cell(b.y), ht_grid_cell(b.z)));
}

// The cells the segment o + t d, t in [t0, t1], meets (t1 up to 3e38 for a miss). The segment is cut where it
// crosses the cell planes of its dominant axis; each piece marks its slab along that axis times the cells between
// its end points along the other two (exact along the dominant axis, a bounding range along the others). Pieces
// share their computed end parameters, so they cover [t0, t1] without gaps; the rounding of the end points stays
// far below HT_GRID_PAD for segments within a hundred grids of the scene. A NaN segment meets every cell.
HT_INLINE uvec2 ht_segment_cells(vec3 o, vec3 d, float t0, float t1, SegmentGrid g) {
  vec3 origin = vec3(g.origin.x, g.origin.y, g.origin.z), scale = vec3(g.scale.x, g.scale.y, g.scale.z);
  vec3 p0 = (o - origin) * scale, v = d * scale;
  if (HT_SEGMENT_NAN(p0.x) || HT_SEGMENT_NAN(p0.y) || HT_SEGMENT_NAN(p0.z) || HT_SEGMENT_NAN(v.x) ||
      HT_SEGMENT_NAN(v.y) || HT_SEGMENT_NAN(v.z) || HT_SEGMENT_NAN(t0) || HT_SEGMENT_NAN(t1))
    return uvec2(0xffffffffu, 0xffffffffu);
  int axis = 2;
  if (abs(v.x) >= abs(v.y) && abs(v.x) >= abs(v.z)) {
    axis = 0;
  } else if (abs(v.y) >= abs(v.z)) {
    axis = 1;
  }
  float pa = p0[axis], va = v[axis];
  uvec2 mask = uvec2(0u, 0u);
  for (uint s = 0u; s < HT_GRID_CELLS; ++s) {
    float lo = t0, hi = t1;
    if (va != 0.0f) {
      // Parameters where the segment's line crosses the slab's lower and upper planes (face slabs: unbounded).
      float tLow = s == 0u ? (va > 0.0f ? -HT_GRID_T_INFINITY : HT_GRID_T_INFINITY) : (float(s) - pa) / va;
      float tHigh =
          s == HT_GRID_CELLS - 1u ? (va > 0.0f ? HT_GRID_T_INFINITY : -HT_GRID_T_INFINITY) : (float(s + 1u) - pa) / va;
      lo = max(t0, min(tLow, tHigh));
      hi = min(t1, max(tLow, tHigh));
    } else if (ht_grid_cell(pa) != s) {
      continue;
    }
    if (!(lo <= hi)) continue;
    vec3 a = p0 + lo * v, b = p0 + hi * v;
    uvec3 ca = uvec3(ht_grid_cell(min(a.x, b.x)), ht_grid_cell(min(a.y, b.y)), ht_grid_cell(min(a.z, b.z)));
    uvec3 cb = uvec3(ht_grid_cell(max(a.x, b.x)), ht_grid_cell(max(a.y, b.y)), ht_grid_cell(max(a.z, b.z)));
    ca[axis] = s;
    cb[axis] = s;
    mask |= ht_grid_box_mask(ca, cb);
  }
  return mask;
}

// Does the segment o + t d, t in [t0, t1], meet the box [lo, hi] (slab test)? The marking pass tests cached primary
// segments against the moved bounds with it, padded by HT_GRID_PAD cells, which is exact where the grid is coarse.
HT_INLINE bool ht_segment_meets_box(vec3 o, vec3 d, float t0, float t1, vec3 lo, vec3 hi) {
  float a = t0, b = t1;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0f) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    float ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
    a = max(a, min(ta, tb));
    b = min(b, max(ta, tb));
  }
  return a <= b;
}

// How far a shadow ray that shade.comp's emit_shadow_rays may trace from the surface point p (known to `pErr` per
// axis) along d (towards a point light at p + d, or to infinity for a directional one) can stray from the points
// p + u d: ht_shadow_meets_box explains the terms.
HT_INLINE float ht_shadow_pad(vec3 p, float pErr, vec3 d, bool directional) {
  float reach = directional ? 0.0f : max(max(abs(d.x), abs(d.y)), abs(d.z));
  HT_PRECISE float offset = (max(max(abs(p.x), abs(p.y)), abs(p.z)) + pErr) * 3.1e-5f + 1.6e-5f;
  HT_PRECISE float pad = pErr + offset + reach * 1e-5f;
  return pad;
}

// Do the points a + u w, u in [0, u1] (u1 may be HT_GRID_T_INFINITY), come within `pad` of the ball (centre ball.xyz,
// radius ball.w)? The nearest point, a + u w with u = (c - a).w / w.w clamped to [0, u1], is computed to a few float
// ULPs of the coordinates' magnitude, so the radius grows by 1e-5 of that magnitude (and 1e-5 of itself): a point
// within the ball is always found, whatever the rounding (of a, a segment's start o + t0 d, too).
HT_INLINE bool ht_points_meet_ball(vec3 a, vec3 w, float u1, float pad, vec4 ball) {
  vec3 c = vec3(ball.x, ball.y, ball.z);
  HT_PRECISE float ww = dot(w, w);
  HT_PRECISE float k = dot(c - a, w);
  float u = ww > 0.0f ? clamp(k / ww, 0.0f, u1) : 0.0f;
  HT_PRECISE vec3 uw = u * w;
  HT_PRECISE vec3 q = a + uw - c;
  HT_PRECISE float mag = max(max(abs(a.x), abs(a.y)), abs(a.z)) + max(max(abs(uw.x), abs(uw.y)), abs(uw.z)) +
                         max(max(abs(c.x), abs(c.y)), abs(c.z));
  HT_PRECISE float r = (ball.w + pad) * 1.00001f + mag * 1e-5f;
  return dot(q, q) <= r * r;
}

// Do the segment o + t d, t in [t0, t1], or the shadow ray from p (as ht_shadow_meets_box) come near one of the moved
// balls (FrameBlock::movedBalls: the moved node's before and after its move; w < 0: none known, so always)? The
// marking pass asks this of the segments that meet the padded moved bounds: a sphere fills half of its box.
HT_INLINE bool ht_segment_meets_balls(vec3 o, vec3 d, float t0, float t1, vec4 ball0, vec4 ball1) {
  if (ball0.w < 0.0f) return true;
  HT_PRECISE vec3 a = o + t0 * d;
  float u1 = t1 >= HT_GRID_T_INFINITY ? HT_GRID_T_INFINITY : t1 - t0;
  return ht_points_meet_ball(a, d, u1, 0.0f, ball0) || ht_points_meet_ball(a, d, u1, 0.0f, ball1);
}
HT_INLINE bool ht_shadow_meets_balls(vec3 p, float pErr, vec4 lightPosition, vec3 direction, vec4 ball0, vec4 ball1) {
  if (ball0.w < 0.0f) return true;
  bool directional = uint(lightPosition.w) == 2u;  // HT_LIGHT_DIRECTIONAL (gpu/wavefront_types.h)
  vec3 d = directional ? -direction : vec3(lightPosition.x, lightPosition.y, lightPosition.z) - p;
  float pad = ht_shadow_pad(p, pErr, d, directional);
  float u1 = directional ? HT_GRID_T_INFINITY : 1.0f;
  return ht_points_meet_ball(p, d, u1, pad, ball0) || ht_points_meet_ball(p, d, u1, pad, ball1);
}

// Does a shadow ray from some point of the box [pLo, pHi] (points known to `pErr` per axis), emitted as
// ht_shadow_meets_box describes, towards the punctual light meet the box [lo, hi]? The points of such rays are, for
// some u, (1 - u) a + u L with a in the box, u in [0, 1] (point and spot lights at L), or a + u w, u >= 0 (a
// directional light, w = -direction). For a fixed u they form a box, so per axis the condition is two linear
// inequalities in u; the rays meet [lo, hi] (grown by the same padding as ht_shadow_meets_box) iff the intervals of u
// they leave intersect. An accumulation's marking pass (mark_accumulated.comp) tests the box of a target's primary
// hit points with it: the box bounds every point from which one of its samples can have sent a shadow ray.
HT_INLINE bool ht_box_shadow_meets_box(vec3 pLo, vec3 pHi, float pErr, vec4 lightPosition, vec3 direction, vec3 lo,
                                       vec3 hi) {
  bool directional = uint(lightPosition.w) == 2u;  // HT_LIGHT_DIRECTIONAL (gpu/wavefront_types.h)
  vec3 light = vec3(lightPosition.x, lightPosition.y, lightPosition.z);
  vec3 far = directional ? vec3(0.0f, 0.0f, 0.0f) : max(abs(light - pLo), abs(light - pHi));
  vec3 mag = max(abs(pLo), abs(pHi));
  HT_PRECISE float offset = (max(max(mag.x, mag.y), mag.z) + pErr) * 3.1e-5f + 1.6e-5f;
  HT_PRECISE float pad = pErr + offset + max(max(far.x, far.y), far.z) * 1e-5f;
  float u0 = 0.0f, u1 = directional ? HT_GRID_T_INFINITY : 1.0f;
  for (int k = 0; k < 3; ++k) {
    float mLo = lo[k] - pad, mHi = hi[k] + pad;
    float qLo = directional ? -direction[k] : light[k] - pLo[k];  // the boxes' low corner moves at qLo per unit u
    float qHi = directional ? -direction[k] : light[k] - pHi[k];
    if (qLo > 0.0f) {  // pLo + u qLo <= mHi
      u1 = min(u1, (mHi - pLo[k]) / qLo);
    } else if (qLo < 0.0f) {
      u0 = max(u0, (mHi - pLo[k]) / qLo);
    } else if (pLo[k] > mHi) {
      return false;
    }
    if (qHi > 0.0f) {  // pHi + u qHi >= mLo
      u0 = max(u0, (mLo - pHi[k]) / qHi);
    } else if (qHi < 0.0f) {
      u1 = min(u1, (mLo - pHi[k]) / qHi);
    } else if (pHi[k] < mLo) {
      return false;
    }
  }
  return u0 <= u1;
}

// The surface point of a cached primary hit, o + t d, and a bound per axis on its distance from the point
// shade.comp interpolates from the triangle's corners (surface_point). Both lie within a few float ULPs of the exact
// intersection: the watertight t is exact to a few ULPs (Woop et al., JCGT 2013) and the interpolation rounds each
// product and sum once, so 2e-5 of the coordinates' magnitude is a bound with margins of 100x.
HT_INLINE vec3 ht_cached_hit_point(vec3 o, vec3 d, float t) {
  HT_PRECISE vec3 p = o + t * d;
  return p;
}
HT_INLINE float ht_cached_hit_error(vec3 o, vec3 d, float t) {
  HT_PRECISE float reach = max(max(abs(o.x), abs(o.y)), abs(o.z)) + abs(t) * max(max(abs(d.x), abs(d.y)), abs(d.z));
  return reach * 2e-5f;
}

// Does a shadow ray that shade.comp's emit_shadow_rays may trace from the surface point p (known to `pErr` per axis)
// towards the punctual light (position.xyz, type HT_LIGHT_* in position.w; `direction` the way a directional light
// travels) meet the box [lo, hi]? Conservative for every emitted ray, whatever the surface's normal:
// - its origin is ht_offset_ray(s.p, n) (bvh/offset_ray.h): each axis moves 256 ULPs of the coordinate (at most
//   |s.p| * 2^-15) or 1/65536 near zero;
// - a point or spot light's ray runs to that origin + dist * normalize(L - s.p), within a few ULPs of |L - s.p| of the
//   segment s.p -> L at every parameter; a directional light's ray is parallel to -direction, to infinity.
// So the segment p -> L (or the ray p - t direction) meets the box grown by pErr + that offset + 1e-5 |L - p|.
HT_INLINE bool ht_shadow_meets_box(vec3 p, float pErr, vec4 lightPosition, vec3 direction, vec3 lo, vec3 hi) {
  bool directional = uint(lightPosition.w) == 2u;  // HT_LIGHT_DIRECTIONAL (gpu/wavefront_types.h)
  vec3 d = directional ? -direction : vec3(lightPosition.x, lightPosition.y, lightPosition.z) - p;
  float pad = ht_shadow_pad(p, pErr, d, directional);
  vec3 grow = vec3(pad, pad, pad);
  return ht_segment_meets_box(p, d, 0.0f, directional ? HT_GRID_T_INFINITY : 1.0f, lo - grow, hi + grow);
}

HT_SHARED_END
#endif
