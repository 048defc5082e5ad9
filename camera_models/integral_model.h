// integral_model.h - primary rays of an integral-imaging / microlens panel (shared C++/GLSL), model M4 of
// docs/OPTICS.md §9.
//
// Geometry (docs/OPTICS.md §7, display-local, z toward the viewer): lens plane z = 0, LCD z = -g. Pixel (x, y) (y from
// the bottom) sits at p = ((x + 0.5 - W/2)*pp, (y + 0.5 - H/2)*pp) (sample position xi instead of 0.5 in "centre"
// mode). Its lens is the nearest lens centre of the rotated, offset grid (lens index = round(R^-1 (p - offset)/pitch),
// the simulator's round(EIShiftInv + EIOrientationInv*p)): c = offset + R*pitch*index. Sample point on the lens:
// s = c ("LensletCenter", pinhole: the ray is the line through p and c, confirmed by the hogel model of
// TLBurnett3/LightField Src/HogelDef/Plane.cpp) or s = c + R*pitch*(xi - 0.5) ("LensletAverage", aperture).
// Emission slope (per unit z toward the viewer) through a thin lens, ray-transfer form theta' = theta - h/f:
//   e_tan = (s - p)/g - (s - c)/f
// (docs/OPTICS.md §7 notes the simulator's d_tan = (p - s)/g - (s - c)/f has the opposite lens-term sign in its
// PupilCenter comment; this sign collimates every aperture sample when g = f, tested in tests/camera_models).
// Front-plane form for scenes in front of and behind the screen (docs/OPTICS.md §7 [derived], §9 M4): e =
// normalize(e_tan, 1), origin = (s, 0) + e*(zFront/e.z) on the plane z = zFront, dir = -e (into the display). zFront =
// L reproduces the simulator's viewer-plane origin (s - d_tan*L, 0).
#ifndef HT_INTEGRAL_MODEL_H
#define HT_INTEGRAL_MODEL_H
#include "common/glsl_cpp.h"
#include "camera_models/integral_params.h"

HT_SHARED_BEGIN

// LCD position (display units) of pixel (x, y) at in-pixel position f in [0,1)^2.
HT_INLINE vec2 integral_pixel_position(IntegralParams p, uint x, uint y, vec2 f) {
  return vec2((float(x) + f.x - 0.5f * p.panel.x) * p.panel.z, (float(y) + f.y - 0.5f * p.panel.y) * p.panel.z);
}

// Lens grid rotation R applied to v.
HT_INLINE vec2 integral_rotate(IntegralParams p, vec2 v) {
  return vec2(p.grid.z * v.x - p.grid.w * v.y, p.grid.w * v.x + p.grid.z * v.y);
}

// p - c: the LCD point of pixel (x, y) at in-pixel position f relative to its nearest lens centre, display units.
// Float precision: p reaches ~W*pp/2 (170 mm on a 15" panel, ulp 1.5e-5 mm) while p - c is below a lens pitch; the
// slope (p - c)/g would lose ~5e-6 rad. The grid coordinate g = x*A + y*B + (f.x*A + f.y*B + g0) is therefore
// evaluated as in lenticular_model.h: A, B split hi + lo so that x*hi, y*hi are exact and fract() drops the integer
// (lens index) part exactly; g0 is reduced mod 1 on the host. Then rel = g - round(g) in [-0.5, 0.5) lens pitches.
HT_INLINE vec2 integral_lens_offset(IntegralParams p, uint x, uint y, vec2 f) {
  vec2 a = vec2(p.rateX.x + p.rateX.y, p.rateX.z + p.rateX.w);
  vec2 b = vec2(p.rateY.x + p.rateY.y, p.rateY.z + p.rateY.w);
  HT_PRECISE float gx = (fract(float(x) * p.rateX.x) + fract(float(y) * p.rateY.x)) +
                        ((float(x) * p.rateX.y + float(y) * p.rateY.y) + (f.x * a.x + f.y * b.x + p.gridConst.x));
  HT_PRECISE float gy = (fract(float(x) * p.rateX.z) + fract(float(y) * p.rateY.z)) +
                        ((float(x) * p.rateX.w + float(y) * p.rateY.w) + (f.x * a.y + f.y * b.y + p.gridConst.y));
  vec2 g = vec2(gx, gy);
  vec2 rel = g - floor(g + vec2(0.5f));
  return integral_rotate(p, rel * p.lens.x);
}

// In-pixel position of sample xi for `view`: view 0, 1, 2 = the R, G, B stripe subpixel (x in [c/3, (c+1)/3) of the
// pixel), HT_INTEGRAL_WHOLE_PIXEL (any other value) = the whole pixel.
HT_CONST uint HT_INTEGRAL_WHOLE_PIXEL = 0xffffffffu;
HT_INLINE vec2 integral_in_pixel(uint view, vec2 xi) {
  return view < 3u ? vec2((float(view) + xi.x) / 3.0f, xi.y) : xi;
}

// Primary ray of LCD pixel (x, y) (y from the bottom), subpixel `view` (see integral_in_pixel); xi in [0,1)^2 samples
// the pixel / subpixel ("centre" mode, at the lens centre) or the lens aperture ("aperture" mode, from the pixel or
// subpixel centre).
HT_INLINE void integral_ray(IntegralParams p, uint x, uint y, uint view, vec2 xi, HT_OUT(vec3) origin,
                            HT_OUT(vec3) dir) {
  bool aperture = p.panel.w > 0.5f;
  vec2 f = integral_in_pixel(view, aperture ? vec2(0.5f) : xi);
  vec2 pixelFromLens = integral_lens_offset(p, x, y, f);                                      // p - c
  vec2 sFromLens = aperture ? integral_rotate(p, (xi - vec2(0.5f)) * p.lens.x) : vec2(0.0f);  // s - c
  vec2 c = integral_pixel_position(p, x, y, f) - pixelFromLens;
  vec2 s = c + sFromLens;
  // e_tan = (s - p)/g - (s - c)/f = ((s - c) - (p - c))/g - (s - c)/f.
  vec2 slope = (sFromLens - pixelFromLens) / p.lens.z - sFromLens / p.lens.y;
  vec3 e = normalize(vec3(slope.x, slope.y, 1.0f));
  vec3 o = vec3(s.x, s.y, 0.0f) + e * (p.lens.w / e.z);
  origin = vec3(p.localToWorld * vec4(o * p.scale.x, 1.0f));
  dir = normalize(mat3(p.localToWorld) * -e);
}

HT_SHARED_END
#endif  // HT_INTEGRAL_MODEL_H
