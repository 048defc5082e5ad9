// simulated_view.h - what an eye at position E sees on a light-field display, computed from the display's own optics
// model: the inverse of the per-subpixel (per-pixel) ray mapping the renderer traces. A display image rendered
// directly, seen through this, approximates a pinhole render from E; a quilt-interleaved image, an image of a wrong
// calibration or the `--debug views` phase pattern show what a viewer would see of them, crosstalk included.
//
// Eye positions are in the model's display-local frame (+x right, +y up, +z toward the viewer, E.z > 0), the frame of
// its parameter block before localToWorld / scale:
//   lenticular       focal rectangle of height camera.y centred on the origin, virtual cameras on the line
//                    y = 0, z = D = camera.x (lenticular_model.h); makeLenticularParams(config, Bounds3{}) gives the
//                    scene-independent frame (size 2 when "auto")
//   projector-array  display units, screen z = 0, observer line z = observerDistance (projector_model.h)
//   integral         display units, lens plane z = 0, LCD z = -gap (integral_model.h)
// Images are linear RGBA float, row 0 = top, 4 floats per pixel; y in the formulas counts from the bottom.
//
// Lenticular (lenticular_model.h, docs/OPTICS.md §3, §9 M2). Subpixel s = (x, y, c) at screen point P_s carries view
// phase t_s and the light of the ray from o(t_s) = (D tan(viewCone (t_s - 0.5)), 0, D) through P_s, i.e. it is seen
// from o(t_s) and along the line through it (horizontal parallax only: the lens sheet spreads light vertically).
// An eye E sees it when the line from P_s through E meets z = D at o(t_s):
//   t_eye(P) = atan((P.x + (E.x - P.x) D / E.z) / D) / viewCone + 0.5,    miss_s = t_s - t_eye(P_s) wrapped to
//   [-1/2, 1/2)  (outside the cone the lens shows its neighbouring lobe, as a real lens sheet does).
// Output pixel (x, y), channel c: the eye looks through the lens over (x, y) along a line of constant phase (the
// slanted lens axis: A dx + B dy = 0 with A, B the phase rates per pixel); in row y + k that line sits at
// x - (B/A) k. In each row the channel-c subpixels within half a lens period (1/(2|A|) px) of it are candidates, and
// the eye's line of sight crosses a channel-c subpixel in that row when the smallest |miss| is within half a
// subpixel's phase width (|A|/6). The value is that subpixel's, from the nearest such row (k = 0, then +-1, +-2, ...,
// the smaller |miss| between +k and -k); without a crossing within the rows of one phase cycle across rows
// (|A|/|B|, at most 8 either way) the candidate of least |miss| stands in. So every output subpixel shows the one
// panel subpixel of its colour that the eye sees within the lens, at most one lens period away.
//
// Projector array (projector_model.h, docs/OPTICS.md §6, §9 M3). Output pixel = screen point S on a W x H grid over the
// Sw x Sh screen. Projector k lights S from pixel H_k^-1 S (through its lens distortion), with light leaving S in the
// horizontal direction from P_k through S; the screen scatters it by the Gaussian of LightFieldDisplayModel
// (w_k = exp(-dA^2 1.11741^2 / as^2), dA = that direction's horizontal angle minus the angle of S -> E, as =
// angular scattering). The value is sum_k w_k v_k / sum_k w_k over the projectors that cover S (bilinear in their
// images); as = 0 keeps the projector of least |dA|. Alpha is the brightness toward the eye, min(1, sum_k w_k): 1 where
// some projector aims (nearly) at the eye, falling to 0 where the eye is outside every projector's lobe (a wall seen
// from beyond its view zone is dark there, whatever the colour says). Uncovered screen points are black, alpha 0.
//
// Integral imaging (integral_model.h, docs/OPTICS.md §7, §9 M4). Output pixel (x, y) of the LCD grid looks through its
// lens (centre c). The model emits LCD point p through aperture point s along slope e = (s - p)/g - (s - c)/f per unit
// z; an eye sees p through s when e = (E.xy - s)/E.z, so p = s - g ((E.xy - s)/E.z + (s - c)/f). "centre" sampling
// uses s = c (pinhole lens); "aperture" sampling averages a 4 x 4 grid of s over the lens. Channel c is sampled
// bilinearly between the channel-c stripe subpixels (centres at x + (c + 0.5)/3); points off the LCD are black (edge
// lenses seen at an angle), and alpha is the fraction of the points that fell on it.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "camera_models/camera_params.h"
#include "camera_models/integral_params.h"
#include "camera_models/projector_params.h"

namespace ht {

// A simulated view: linear RGBA float, row 0 = top.
struct SimulatedView {
  std::uint32_t width = 0, height = 0;
  std::vector<float> rgba;
};

// `panel`: the native panel image (screenW x screenH, the layout of a direct lenticular render or of
// interleaveQuilt). Throws Error if the panel size does not match or E.z <= 0.
SimulatedView simulateLenticularView(const gpu_shared::LenticularParams& params, std::span<const float> panel,
                                     glm::dvec3 eye, unsigned threads = 0);

// `images`: the N projector images of width x height one after the other, projector 0 first (a projector-array
// render). `screenSize`: Sw x Sh in display units. The output is outWidth x outHeight over the screen.
// Throws Error if the images do not match, a size is 0 or E.z <= 0.
SimulatedView simulateProjectorView(const gpu_shared::ProjectorArrayParams& params, glm::dvec2 screenSize,
                                    std::uint32_t width, std::uint32_t height, std::span<const float> images,
                                    glm::dvec3 eye, glm::uvec2 outSize, unsigned threads = 0);

// `lcd`: the LCD image (panel.x x panel.y, the layout of an integral render). Throws Error if the size does not
// match or E.z <= 0.
SimulatedView simulateIntegralView(const gpu_shared::IntegralParams& params, std::span<const float> lcd, glm::dvec3 eye,
                                   unsigned threads = 0);

// Eyes spread across each model's view cone, left to right, at bin centres (i + 0.5)/n of it (one eye: the centre):
//   lenticular: the virtual camera line, o(t) = (D tan(viewCone (t - 0.5)), 0, D) for t = (i + 0.5)/n;
//   projector array: on the observer line (z = Dobs, y = h), at the angles seen from the screen centre that span the
//     projectors' emission directions (their extreme projectors' angles as the cone's edges);
//   integral: at z = viewerDistance on y = 0, across the slopes +-lensPitch/(2 gap) an elemental image spans.
std::vector<glm::dvec3> lenticularViewConeEyes(const gpu_shared::LenticularParams& params, std::uint32_t count);
std::vector<glm::dvec3> projectorViewConeEyes(const gpu_shared::ProjectorArrayParams& params, std::uint32_t count);
std::vector<glm::dvec3> integralViewConeEyes(const gpu_shared::IntegralParams& params, double viewerDistance,
                                             std::uint32_t count);

}  // namespace ht
