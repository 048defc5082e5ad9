// lenticular_model.h - direct per-subpixel primary rays for a Looking Glass lenticular panel (shared C++/GLSL).
//
// Model M2 of docs/OPTICS.md §9: the vendor view phase (holoplaycore.js `GetSubpixelViews`, docs/OPTICS.md §3.1; Gen3
// cells `GetCellForPixel`/`GetPixelShift`, §3.2) picks a point on the view cone, the camera of looking-glass-webxr
// `LookingGlassXRDevice.ts onFrameStart` (docs/OPTICS.md §4.3 / §9 M1) turns it into a ray through the focal rectangle.
//
// Conventions (docs/OPTICS.md §0): pixel (x, y) with y counted from the BOTTOM, c = 0, 1, 2 = R, G, B; display-local
// frame +x right, +y up, +z toward the viewer, origin at the centre of the focal rectangle; t = 0 is the leftmost view.
//
// Sampling: xi in [0,1)^2 is the position inside the subpixel's footprint, a rectangle 1/3 px wide and 1 px tall
// centred on the vendor's sample point (u + c*subp, v) (classic) or on the Gen3 cell-offset position. xi = (0.5, 0.5)
// reproduces the vendor formula; other xi move the sample point, and the phase is evaluated at the moved point, so
// averaging over xi prefilters across views (docs/OPTICS.md §8 item 4).
//
// Float precision: phi = x*A + y*B + small, A = pitch_s/W, B = tilt*pitch_s/H, reaches ~1000 on 8K panels where one
// float ulp is 6e-5. makeLenticularParams() therefore stores A and B split into hi + lo parts (cellOffset[0].zw and
// cellOffset[1].zw, computed in double): hi has few enough significant bits that x*hi is exact in float, so fract()
// removes the integer part exactly and the remaining terms are small (error ~1e-7, see tests/camera_models).
// Parameter blocks built by hand with those slots zero fall back to A = pitch_s/W in float (error ~phi*6e-8).
#ifndef HT_LENTICULAR_MODEL_H
#define HT_LENTICULAR_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/camera_params.h"

HT_SHARED_BEGIN

// The Gen3 cell layout (pattern mode, cell count) is read through these macros, which a kernel may define as
// specialisation constants (raygen.comp): the cell code then folds to the one pattern the panel has, or vanishes on
// classic panels. On a CPU Vulkan driver (lavapipe) the generic code cost time even where no ray took it: 0.3 s of
// a 0.8 s raygen on the Portrait (no cells) and 0.5 s of 2.2 s on the Gen3 16" (docs/BENCHMARKS.md).
#ifndef HT_LENTICULAR_CELL_MODE
#define HT_LENTICULAR_CELL_MODE(p) (p).flags.x
#define HT_LENTICULAR_CELL_COUNT(p) (p).flags.y
#endif

// Largest float below 1: t stays in [0, 1) when rounding pushes it up to 1.
HT_CONST float HT_LENTICULAR_T_MAX = 0.99999994f;

// Channel whose physical subpixel feeds output channel c: BGR panels (flipSubp) swap R and B, c' = 2 - c
// (HoloPlayCore ri/bi, docs/OPTICS.md §1 and §9 M2).
HT_INLINE uint lenticular_physical_channel(LenticularParams p, uint c) { return p.panel.w > 0.5f ? 2u - c : c; }

// Whether the panel places its subpixels by Gen3 cells (docs/OPTICS.md §3.2) rather than the classic 1/3-pixel steps.
HT_INLINE bool lenticular_has_cells(LenticularParams p) {
  return HT_LENTICULAR_CELL_MODE(p) != 0 && HT_LENTICULAR_CELL_COUNT(p) > 0;
}

// Gen3 subpixel cell of pixel (x, y), y from the bottom (holoplaycore.js GetCellForPixel, docs/OPTICS.md §3.2).
HT_INLINE uint lenticular_cell(LenticularParams p, uint x, uint y) {
  int mode = HT_LENTICULAR_CELL_MODE(p);
  uint cell = 0u;
  if (mode == 1) cell = ((x % 2u) == (y % 2u)) ? 0u : 1u;  // checkerboard
  if (mode == 2) cell = x % 2u;
  if (mode == 3) cell = (y + (x % 2u) * 2u) % 4u;
  if (mode == 4) cell = y % 2u;
  uint count = uint(max(HT_LENTICULAR_CELL_COUNT(p), 1));
  return cell % count;
}

// Sample point of subpixel (x, y, c) at footprint position xi, as an offset in pixels from the pixel's lower-left
// corner: the sample lies at ((x, y) + offset) / (W, H) in screen uv.
//   classic: centre (0.5 + c*subp*W, 0.5) = (0.5 +- c/3, 0.5) (subp = +-1/(3W), docs/OPTICS.md §2 / §3.1)
//   Gen3:    centre (0.5 + offX, 0.5 + offY) with offsets in pixels (docs/OPTICS.md §3.2)
HT_INLINE vec2 lenticular_sample_offset_px(LenticularParams p, uint x, uint y, uint c, vec2 xi) {
  uint cp = lenticular_physical_channel(p, c);
  vec2 centre = vec2(0.5f, 0.5f);
  if (lenticular_has_cells(p)) {
    // Select instead of a dynamic index: an indexed array inside a by-value struct becomes per-lane scratch
    // memory on lavapipe (2.4x slower raygen, measured), a select chain stays in registers.
    uint idx = lenticular_cell(p, x, y) * 3u + cp;
    vec4 cellOffset = p.cellOffset[0];
    for (uint k = 1u; k < 3u * HT_MAX_SUBPIXEL_CELLS; ++k) cellOffset = k == idx ? p.cellOffset[k] : cellOffset;
    centre = vec2(0.5f + cellOffset.x * p.panel.x, 0.5f + cellOffset.y * p.panel.y);
  } else {
    float subpSign = p.phase.z < 0.0f ? -1.0f : 1.0f;
    centre = vec2(0.5f + subpSign * float(cp) / 3.0f, 0.5f);
  }
  return vec2(centre.x + (xi.x - 0.5f) / 3.0f, centre.y + (xi.y - 0.5f));
}

// Screen uv (v from the bottom) of the sample point.
HT_INLINE vec2 lenticular_uv_at_offset(LenticularParams p, uint x, uint y, vec2 o) {
  return vec2((float(x) + o.x) / p.panel.x, (float(y) + o.y) / p.panel.y);
}
HT_INLINE vec2 lenticular_sample_uv(LenticularParams p, uint x, uint y, uint c, vec2 xi) {
  return lenticular_uv_at_offset(p, x, y, lenticular_sample_offset_px(p, x, y, c, xi));
}

// Phase rate per pixel, split hi + lo. The host stores (hi, lo); a zero pair falls back to the float quotient.
HT_INLINE vec2 lenticular_rate_split(vec2 stored, float fallback) {
  return (stored.x == 0.0f && stored.y == 0.0f) ? vec2(fallback, 0.0f) : stored;
}

// View phase t in [0, 1) of subpixel (x, y, c) at footprint position xi (docs/OPTICS.md §3.1, §3.2, §9 M2):
//   phi = (u_s + v_s*tilt)*pitch_s - center,   u_s, v_s = sample point (includes c*subp or the Gen3 offsets)
//   t   = invView ? 1 - fract(phi) : fract(phi)
// evaluated as phi = fract(x*A_hi) + fract(y*B_hi) + (x*A_lo + y*B_lo + ox*A + oy*B - center), where
// A = pitch_s/W, B = tilt*pitch_s/H and (ox, oy) = lenticular_sample_offset_px; x*A_hi and y*B_hi are exact.
// lenticular_view_phase_at_offset: the same at a sample offset o = lenticular_sample_offset_px(p, x, y, c, xi).
HT_INLINE float lenticular_view_phase_at_offset(LenticularParams p, uint x, uint y, vec2 o) {
  vec2 rateX = lenticular_rate_split(vec2(p.cellOffset[0].z, p.cellOffset[0].w), p.phase.x / p.panel.x);
  vec2 rateY = lenticular_rate_split(vec2(p.cellOffset[1].z, p.cellOffset[1].w), p.phase.y * p.phase.x / p.panel.y);
  HT_PRECISE float fx = fract(float(x) * rateX.x);
  HT_PRECISE float fy = fract(float(y) * rateY.x);
  HT_PRECISE float small = float(x) * rateX.y + float(y) * rateY.y;
  HT_PRECISE float local = o.x * (rateX.x + rateX.y) + o.y * (rateY.x + rateY.y) - p.phase.w;
  HT_PRECISE float f = fract((fx + fy) + (small + local));
  float t = p.panel.z > 0.5f ? 1.0f - f : f;
  return min(t, HT_LENTICULAR_T_MAX);
}
HT_INLINE float lenticular_view_phase(LenticularParams p, uint x, uint y, uint c, vec2 xi) {
  return lenticular_view_phase_at_offset(p, x, y, lenticular_sample_offset_px(p, x, y, c, xi));
}

// Ray for view phase t through the focal-plane point at screen uv (docs/OPTICS.md §9 M1/M2, looking-glass-webxr
// camera):
//   theta = viewCone*(t - 0.5);  o = (D tan(theta), 0, D)
//   P = ((u - 0.5)*aspect*size, (v - 0.5)*size, 0), u, v mirrored by flipImageX / flipImageY;  d = normalize(P - o)
// then display-local -> world through localToWorld. dir is unit length.
HT_INLINE void lenticular_ray_for_phase(LenticularParams p, float t, vec2 uv, HT_OUT(vec3) origin, HT_OUT(vec3) dir) {
  float focalDistance = p.camera.x;
  float size = p.camera.y;
  float aspect = p.camera.z;
  float theta = p.camera.w * (t - 0.5f);
  vec3 o = vec3(focalDistance * tan(theta), 0.0f, focalDistance);
  float u = p.flags.z != 0 ? 1.0f - uv.x : uv.x;
  float v = p.flags.w != 0 ? 1.0f - uv.y : uv.y;
  vec3 target = vec3((u - 0.5f) * aspect * size, (v - 0.5f) * size, 0.0f);
  vec3 d = normalize(target - o);
  origin = vec3(p.localToWorld * vec4(o, 1.0f));
  dir = normalize(mat3(p.localToWorld) * d);
}

// Primary ray of subpixel (x, y, c) (y from the bottom) at footprint position xi in [0,1)^2.
HT_INLINE void lenticular_ray(LenticularParams p, uint x, uint y, uint c, vec2 xi, HT_OUT(vec3) origin,
                              HT_OUT(vec3) dir) {
  vec2 o = lenticular_sample_offset_px(p, x, y, c, xi);
  lenticular_ray_for_phase(p, lenticular_view_phase_at_offset(p, x, y, o), lenticular_uv_at_offset(p, x, y, o), origin,
                           dir);
}

HT_SHARED_END
#endif  // HT_LENTICULAR_MODEL_H
