// watertight_triangle.h - watertight ray/triangle intersection (C++ and GLSL).
//
// Algorithm: Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1) 2013, with the details of
// pbrt-v3 src/shapes/triangle.cpp (docs/BVH.md §5.1):
//  1. per ray: kz = argmax |D|, kx = kz+1 mod 3, ky = kx+1 mod 3; Sx = Dx/Dz, Sy = Dy/Dz, Sz = 1/Dz (indices
//     permuted). Both windings are accepted (pbrt-v3), so kx/ky are not swapped for Dz < 0.
//  2. translate each vertex by -O and shear: x = P[kx] - Sx*P[kz], y = P[ky] - Sy*P[kz] (P = vertex - O).
//     The transform of a vertex does not depend on the triangle, so two triangles sharing an edge compute
//     bit-identical edge functions of opposite sign: no ray passes between them (watertightness).
//  3. edge functions U = Cx*By - Cy*Bx, V = Ax*Cy - Ay*Cx, W = Bx*Ay - By*Ax; if any is exactly 0 they are
//     recomputed in double (products of two floats are exact in double, so the sign is exact): pbrt-v3
//     "Fall back to double precision test at triangle edges".
//  4. reject mixed signs and det = U+V+W == 0; compare T = U*Az + V*Bz + W*Cz (z scaled by Sz) with det*tmin
//     and det*tmax after matching signs, dividing only for accepted hits.
//  5. pbrt-v3's conservative bound: accept only t > deltaT (gamma(2/3/5) error terms), so no hit is reported
//     at or just behind the origin; a hit the float bound cannot confirm is rechecked in double
//     (ht_confirm_t_double), because the float bound alone rejected real hits at edges (docs/ACCURACY.md).
// Edge values are computed without FMA: C++ builds with -ffp-contract=off, GLSL marks them `precise`.
#ifndef HT_WATERTIGHT_TRIANGLE_H
#define HT_WATERTIGHT_TRIANGLE_H
#include "common/glsl_cpp.h"
#include "bvh/float_bounds.h"
#include "common/exact_division.h"

HT_SHARED_BEGIN

// Per-ray precomputation of the watertight test (done once per ray).
struct HtWatertightRay {
  uint kx, ky, kz;   // permutation: kz = dominant direction axis
  float Sx, Sy, Sz;  // shear constants
  float ox, oy, oz;  // origin permuted as (O[kx], O[ky], O[kz])
  float tmin;
};

HT_INLINE HtWatertightRay ht_make_watertight_ray(vec3 origin, vec3 dir, float tmin) {
  HtWatertightRay r;
  vec3 ad = abs(dir);
  r.kz = ad.x > ad.y ? (ad.x > ad.z ? 0u : 2u) : (ad.y > ad.z ? 1u : 2u);
  r.kx = r.kz == 2u ? 0u : r.kz + 1u;
  r.ky = r.kx == 2u ? 0u : r.kx + 1u;
  float dz = dir[r.kz];
  r.Sx = ht_div(dir[r.kx], dz);
  r.Sy = ht_div(dir[r.ky], dz);
  r.Sz = ht_div(1.0f, dz);
  r.ox = origin[r.kx];
  r.oy = origin[r.ky];
  r.oz = origin[r.kz];
  r.tmin = tmin;
  return r;
}

// Vertex translated by -O and sheared: (x, y, z) with z NOT yet scaled by Sz.
HT_INLINE vec3 ht_shear_vertex(HT_IN(HtWatertightRay) r, vec3 p) {
  HT_PRECISE float z = p[r.kz] - r.oz;
  HT_PRECISE float x = (p[r.kx] - r.ox) - r.Sx * z;
  HT_PRECISE float y = (p[r.ky] - r.oy) - r.Sy * z;
  return vec3(x, y, z);
}

// Edge function p.x*q.y - p.y*q.x evaluated in double: both products are exact, so the sign is exact.
HT_INLINE float ht_edge_double(vec3 p, vec3 q) {
  HT_PRECISE double e = double(p.x) * double(q.y) - double(p.y) * double(q.x);
  return float(e);
}

// Double-precision recheck of pbrt-v3's "t > deltaT" for a hit whose float bound could not confirm it.
// The float bound is loose where the edge functions are small against the vertex coordinates (grazing or
// needle triangles, rays through an edge): deltaT then exceeds t even for hits far from the origin, and since
// deltaT differs between the two triangles of an edge, rejecting there opens a hole (docs/ACCURACY.md). The
// sign decisions stay the float ones (watertightness); only t and its bound are redone with the same formulas
// (pbr-book 3rd ed. §3.9.6) in double, gamma(n) = n u / (1 - n u) with u = 2^-53, where the bound is 2^29 times
// tighter. A hit at or behind the origin is still rejected.
HT_INLINE bool ht_confirm_t_double(HT_IN(HtWatertightRay) r, vec3 a, vec3 b, vec3 c) {
  HT_PRECISE double az = double(a[r.kz]) - double(r.oz);
  HT_PRECISE double bz = double(b[r.kz]) - double(r.oz);
  HT_PRECISE double cz = double(c[r.kz]) - double(r.oz);
  HT_PRECISE double ax = (double(a[r.kx]) - double(r.ox)) - double(r.Sx) * az;
  HT_PRECISE double ay = (double(a[r.ky]) - double(r.oy)) - double(r.Sy) * az;
  HT_PRECISE double bx = (double(b[r.kx]) - double(r.ox)) - double(r.Sx) * bz;
  HT_PRECISE double by = (double(b[r.ky]) - double(r.oy)) - double(r.Sy) * bz;
  HT_PRECISE double cx = (double(c[r.kx]) - double(r.ox)) - double(r.Sx) * cz;
  HT_PRECISE double cy = (double(c[r.ky]) - double(r.oy)) - double(r.Sy) * cz;
  HT_PRECISE double U = cx * by - cy * bx;
  HT_PRECISE double V = ax * cy - ay * cx;
  HT_PRECISE double W = bx * ay - by * ax;
  HT_PRECISE double det = U + V + W;
  if (det == 0.0) return false;
  double sz = double(r.Sz);
  HT_PRECISE double T = U * (sz * az) + V * (sz * bz) + W * (sz * cz);
  HT_PRECISE double t = T / det;
  const double g2 = 2.2204460492503136e-16, g3 = 3.3306690738754696e-16, g5 = 5.5511151231257852e-16;
  double maxZt = max(abs(sz * az), max(abs(sz * bz), abs(sz * cz)));
  double maxZ = max(abs(az), max(abs(bz), abs(cz)));
  double maxX = max(abs(ax), max(abs(bx), abs(cx)));
  double maxY = max(abs(ay), max(abs(by), abs(cy)));
  double maxE = max(abs(U), max(abs(V), abs(W)));
  HT_PRECISE double deltaX = g5 * (maxX + maxZ);
  HT_PRECISE double deltaY = g5 * (maxY + maxZ);
  HT_PRECISE double deltaE = 2.0 * (g2 * maxX * maxY + deltaY * maxX + deltaX * maxY);
  HT_PRECISE double deltaT = 3.0 * (g3 * maxE * maxZt + deltaE * maxZt + g3 * maxZt * maxE) / abs(det);
  return t > deltaT;
}

// Watertight intersection of the ray with triangle (a, b, c) within [tmin, tmax].
// On a hit returns true with t and the barycentrics u (of b) and v (of c); otherwise returns false and
// leaves t = tmax, u = v = 0.
HT_INLINE bool ht_intersect_triangle(HT_IN(HtWatertightRay) r, vec3 a, vec3 b, vec3 c, float tmax, HT_OUT(float) t,
                                     HT_OUT(float) u, HT_OUT(float) v) {
  t = tmax;
  u = 0.0f;
  v = 0.0f;
  vec3 A = ht_shear_vertex(r, a);
  vec3 B = ht_shear_vertex(r, b);
  vec3 C = ht_shear_vertex(r, c);
  HT_PRECISE float U = C.x * B.y - C.y * B.x;
  HT_PRECISE float V = A.x * C.y - A.y * C.x;
  HT_PRECISE float W = B.x * A.y - B.y * A.x;
  if (U == 0.0f || V == 0.0f || W == 0.0f) {
    U = ht_edge_double(C, B);
    V = ht_edge_double(A, C);
    W = ht_edge_double(B, A);
  }
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return false;
  HT_PRECISE float det = U + V + W;
  if (det == 0.0f) return false;
  HT_PRECISE float Az = r.Sz * A.z;
  HT_PRECISE float Bz = r.Sz * B.z;
  HT_PRECISE float Cz = r.Sz * C.z;
  HT_PRECISE float T = U * Az + V * Bz + W * Cz;
  // Make det positive (multiplying by +-1 is exact), then test T in [tmin*det, tmax*det] without dividing.
  float sgn = det < 0.0f ? -1.0f : 1.0f;
  HT_PRECISE float detAbs = det * sgn;
  HT_PRECISE float TAbs = T * sgn;
  if (!(TAbs > 0.0f) || TAbs < r.tmin * detAbs || TAbs > tmax * detAbs) return false;

  HT_PRECISE float invDet = ht_div(1.0f, det);
  HT_PRECISE float tHit = T * invDet;
  // pbrt-v3 triangle.cpp: conservative error bound deltaT on t (pbr-book 3rd ed. §3.9.6).
  // Units: maxZt is a scaled z (t units, z * Sz); the shear error of x and y (deltaX, deltaY) is in coordinate
  // units and comes from x = (P[kx] - O[kx]) - Sx * z with the UNscaled z and |Sx| <= 1 (5 roundings), so it
  // takes maxZ = max |z| before scaling. pbrt-v3 uses the scaled maxZt there, which mixes units: for
  // |D| << scene size (e.g. D = target - origin on a 1e-4 scale mesh) deltaT then exceeds t and real hits
  // were rejected (leaks found by tests/accuracy, docs/ACCURACY.md); for |D| >> 1 the bound was too small.
  float maxZt = max(abs(Az), max(abs(Bz), abs(Cz)));
  float maxZ = max(abs(A.z), max(abs(B.z), abs(C.z)));
  float maxXt = max(abs(A.x), max(abs(B.x), abs(C.x)));
  float maxYt = max(abs(A.y), max(abs(B.y), abs(C.y)));
  HT_PRECISE float deltaZ = HT_GAMMA3 * maxZt;
  HT_PRECISE float deltaX = HT_GAMMA5 * (maxXt + maxZ);
  HT_PRECISE float deltaY = HT_GAMMA5 * (maxYt + maxZ);
  HT_PRECISE float deltaE = 2.0f * (HT_GAMMA2 * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
  float maxE = max(abs(U), max(abs(V), abs(W)));
  HT_PRECISE float deltaT = 3.0f * (HT_GAMMA3 * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * abs(invDet);
  // Also keep the rounded t itself inside [tmin, tmax], so a hit never lies beyond the caller's tmax.
  if (tHit < r.tmin || tHit > tmax) return false;
  if (tHit <= deltaT && !ht_confirm_t_double(r, a, b, c)) return false;

  t = tHit;
  HT_PRECISE float uHit = V * invDet;
  HT_PRECISE float vHit = W * invDet;
  u = uHit;
  v = vHit;
  return true;
}

HT_SHARED_END
#endif
