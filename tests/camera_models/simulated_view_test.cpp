// simulated_view_test.cpp - the simulated viewer as an oracle: a display image "rendered" directly (every subpixel's
// model ray shaded by an analytic scene, a textured plane behind the screen) and seen through simulate*View from eye
// E matches a pinhole view of the same scene from E, and fails to match the pinhole view from another eye; the
// lenticular phase pattern seen from a camera position is that camera's view; projector coverage; the eye lines.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "camera_models/display_config.h"
#include "camera_models/integral_model.h"
#include "camera_models/integral_setup.h"
#include "camera_models/lenticular_model.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/projector_model.h"
#include "camera_models/projector_setup.h"
#include "camera_models/simulated_view.h"
#include "common/error.h"
#include "tests/camera_models/camera_test_support.h"

namespace ht::test {
namespace {

// A textured plane z = kPlaneZ (world units) behind the screen: smooth colour waves of period 1, a different phase per
// channel. Rays that never reach it see 0.
constexpr double kPlaneZ = -0.6;
float planeRadiance(glm::dvec3 origin, glm::dvec3 dir, std::uint32_t c) {
  if (!(dir.z < 0.0)) return 0.0f;
  const double s = (kPlaneZ - origin.z) / dir.z;
  const glm::dvec3 hit = origin + s * dir;
  const double twoPi = 6.283185307179586;
  return float(0.5 + 0.3 * std::sin(twoPi * hit.x + 1.1 * c) * std::cos(twoPi * 0.8 * hit.y - 0.7 * c));
}

glm::dvec3 worldPoint(const glm::mat4& localToWorld, double scale, glm::dvec3 local) {
  return glm::dvec3(glm::dmat4(localToWorld) * glm::dvec4(local * scale, 1.0));
}

float pinholeRadiance(glm::dvec3 eyeWorld, glm::dvec3 targetWorld, std::uint32_t c) {
  return planeRadiance(eyeWorld, glm::normalize(targetWorld - eyeWorld), c);
}

// PSNR (dB, peak 1) over R, G, B of two RGBA images, on the pixels where `a` has full alpha (the simulated view's
// pixels the eye sees at full brightness).
double psnr(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (i % 4 == 3 || a[i - i % 4 + 3] < 1.0f) continue;
    sum += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    ++n;
  }
  return 10.0 * std::log10(1.0 / (sum / double(n)));
}

// Fraction of the pixels with full alpha.
double fullyLit(const std::vector<float>& rgba) {
  std::size_t n = 0;
  for (std::size_t i = 3; i < rgba.size(); i += 4) n += rgba[i] >= 1.0f;
  return double(n) / double(rgba.size() / 4);
}

// An RGBA image (row 0 = top) whose channel c at (x, y from the bottom) is value(x, y, c).
std::vector<float> imageOf(std::uint32_t w, std::uint32_t h,
                           const std::function<float(std::uint32_t, std::uint32_t, std::uint32_t)>& value) {
  std::vector<float> rgba(std::size_t(w) * h * 4, 1.0f);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x)
      for (std::uint32_t c = 0; c < 3; ++c) rgba[(std::size_t(h - 1 - y) * w + x) * 4 + c] = value(x, y, c);
  return rgba;
}

// ---- lenticular ----------------------------------------------------------------------------------------------------

// 192x128 panels with the Portrait's phase rates (0.16 phase per pixel across, -0.022 per row); cellMode 2 = the
// 16" Gen3 template cells.
DisplayConfig lenticularPanel(int cellMode = 0) {
  const std::string cells = cellMode == 0 ? "[]" : R"([{"ROffsetX":-0.31,"ROffsetY":0.25,"GOffsetX":0.28,
      "GOffsetY":0.25,"BOffsetX":0,"BOffsetY":-0.25},{"ROffsetX":-0.31,"ROffsetY":-0.25,"GOffsetX":0.28,"GOffsetY":-0.25,"BOffsetX":0,
      "BOffsetY":0.25}])";
  return parseDisplayConfig(std::string(R"({"name": "sim", "calibration": {"pitch": 52.59, "slope": -7.21,
      "center": 0.40, "viewCone": 40, "invView": 1, "DPI": 324, "screenW": 192, "screenH": 128, "flipImageX": 0,
      "flipImageY": 0, "flipSubp": 0, "CellPatternMode": )") +
                                std::to_string(cellMode) + R"(, "subpixelCells": )" + cells + "}}",
                            "sim.json", "");
}

// Focal-plane point (display-local) of subpixel (x, y, c)'s sample point, mirrored like lenticular_ray_for_phase.
glm::dvec3 lenticularFocalPoint(const gpu_shared::LenticularParams& p, std::uint32_t x, std::uint32_t y,
                                std::uint32_t c) {
  glm::dvec2 uv = glm::dvec2(gpu_shared::lenticular_sample_uv(p, x, y, c, glm::vec2(0.5f)));
  if (p.flags.z != 0) uv.x = 1.0 - uv.x;
  if (p.flags.w != 0) uv.y = 1.0 - uv.y;
  return {(uv.x - 0.5) * p.camera.z * p.camera.y, (uv.y - 0.5) * p.camera.y, 0.0};
}

std::vector<float> directLenticularPanel(const gpu_shared::LenticularParams& p) {
  return imageOf(std::uint32_t(p.panel.x), std::uint32_t(p.panel.y), [&](auto x, auto y, auto c) {
    glm::vec3 o, d;
    gpu_shared::lenticular_ray(p, x, y, c, glm::vec2(0.5f), o, d);
    return planeRadiance(glm::dvec3(o), glm::dvec3(d), c);
  });
}

std::vector<float> lenticularPinhole(const gpu_shared::LenticularParams& p, glm::dvec3 eye) {
  const glm::dvec3 eyeWorld = worldPoint(p.localToWorld, 1.0, eye);
  return imageOf(std::uint32_t(p.panel.x), std::uint32_t(p.panel.y), [&](auto x, auto y, auto c) {
    return pinholeRadiance(eyeWorld, worldPoint(p.localToWorld, 1.0, lenticularFocalPoint(p, x, y, c)), c);
  });
}

// The eyes across the cone (and one at 1.4 D, where each screen region shows another view) see the direct panel as
// the pinhole camera at their position sees the scene; a pinhole at the mirrored eye does not. Error budget: the
// subpixel the eye sees lies up to half a lens period (3.1 px = 0.049 units) from the output pixel, which the colour
// waves (slope up to 2 pi 0.3 per unit) turn into errors up to ~0.09, RMS ~0.03 (30 dB); its view is within half a
// subpixel (1/6 of a lens's phase, 1.1 degrees) of the eye's, a 0.01-unit shift on the plane 0.6 behind. Measured:
// 27.4-27.5 dB for every eye and both panels (deterministic); the mirrored eye 11.6-21.1 dB.
TEST(SimulatedLenticularView, DirectRenderSeenFromAnEyeIsThePinholeViewFromThere) {
  for (int cellMode : {0, 2}) {
    const gpu_shared::LenticularParams p = makeLenticularParams(lenticularPanel(cellMode), Bounds3{});
    const std::vector<float> panel = directLenticularPanel(p);
    std::vector<glm::dvec3> eyes = lenticularViewConeEyes(p, 5);
    eyes.push_back(glm::dvec3(0.8, 0.0, 1.4 * p.camera.x));
    for (const glm::dvec3& eye : eyes) {
      const SimulatedView seen = simulateLenticularView(p, panel, eye, 2);
      ASSERT_EQ(seen.width, 192u);
      ASSERT_EQ(seen.height, 128u);
      const double right = psnr(seen.rgba, lenticularPinhole(p, eye));
      const double wrong = psnr(seen.rgba, lenticularPinhole(p, glm::dvec3(-eye.x, eye.y, eye.z)));
      EXPECT_GT(right, 26.5) << "cell mode " << cellMode << ", eye x " << eye.x << " z " << eye.z;
      if (std::fabs(eye.x) > 0.5) { EXPECT_GT(right, wrong + 6.0) << "cell mode " << cellMode << ", eye x " << eye.x; }
    }
  }
}

// The `--debug views` picture: every subpixel shows its own view phase t. From a camera position o(t_e) the eye sees
// t_e on the whole screen, to within half a subpixel's phase width (|A|/6) where its line of sight crosses a subpixel
// of that colour within the searched rows, and within half a lens's phase step (|A|/2) anywhere. From 1.4 D each
// screen point shows the view whose camera the line from it through the eye meets.
TEST(SimulatedLenticularView, PhasePatternShowsTheViewOfTheEyesCamera) {
  const gpu_shared::LenticularParams p = makeLenticularParams(lenticularPanel(), Bounds3{});
  const auto w = std::uint32_t(p.panel.x), h = std::uint32_t(p.panel.y);
  const std::vector<float> phases = imageOf(
      w, h, [&](auto x, auto y, auto c) { return gpu_shared::lenticular_view_phase(p, x, y, c, glm::vec2(0.5f)); });
  const double a = double(p.phase.x) / p.panel.x;  // phase per pixel
  const double d = p.camera.x, cone = p.camera.w;
  std::vector<glm::dvec3> eyes = lenticularViewConeEyes(p, 4);
  eyes.push_back(glm::dvec3(-0.5, 0.3, 1.4 * d));
  for (const glm::dvec3& eye : eyes) {
    const SimulatedView seen = simulateLenticularView(p, phases, eye, 2);
    std::size_t within = 0, total = 0;
    double worst = 0.0;
    for (std::uint32_t y = 0; y < h; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        for (std::uint32_t c = 0; c < 3; ++c) {
          const glm::dvec3 focal = lenticularFocalPoint(p, x, y, c);
          const double cameraX = focal.x + (eye.x - focal.x) * d / eye.z;
          const double want = std::atan(cameraX / d) / cone + 0.5;
          const double miss = std::fabs(phaseDifference(seen.rgba[(std::size_t(h - 1 - y) * w + x) * 4 + c], want));
          // Within 4 px (half a lens period) of the left and right edges part of the lens is missing.
          if (x >= 4 && x + 4 < w) worst = std::max(worst, miss);
          // The seen subpixel lies up to 3 px from (x, y); from 1.4 D the phase the eye needs changes by at most
          // 0.0024 over 3 px (0.047 units * (1 - D/E.z) / (D viewCone)), from D not at all.
          within += miss <= std::fabs(a) / 6.0 + 0.003;
          ++total;
        }
      }
    }
    EXPECT_LE(worst, std::fabs(a) / 2.0 + 0.003) << "eye x " << eye.x;
    EXPECT_GE(double(within) / double(total), 0.98) << "eye x " << eye.x;
  }
}

TEST(SimulatedLenticularView, BadInputsAreErrors) {
  const gpu_shared::LenticularParams p = makeLenticularParams(lenticularPanel(), Bounds3{});
  const std::vector<float> panel(192 * 128 * 4, 0.5f);
  EXPECT_THROW(simulateLenticularView(p, std::vector<float>(16, 0.0f), {0, 0, 8}), Error);
  EXPECT_THROW(simulateLenticularView(p, panel, {0, 0, 0}), Error);   // in the screen plane
  EXPECT_THROW(simulateLenticularView(p, panel, {0, 0, -3}), Error);  // behind it
  EXPECT_THROW(simulateLenticularView(p, panel, {NAN, 0, 8}), Error);
}

// ---- projector array -----------------------------------------------------------------------------------------------

// 37 projectors 10 units apart over +-180, 180 behind a 160 x 90 screen, observer line 300 in front: 3.2 degrees
// between neighbours, auto scattering 1.5 x that. From the observer line at x, screen point S is lit toward the eye by
// the projector at 1.6 S.x - 0.6 x, so the array is wider than the screen.
DisplayConfig projectorWall() {
  std::string projectors;
  for (int k = -18; k <= 18; ++k) {
    projectors +=
        std::string(projectors.empty() ? "" : ", ") + R"({"position": [)" + std::to_string(10 * k) + ", 0, -180]}";
  }
  return parseDisplayConfig(R"({"name": "wall", "model": "projector-array", "projectorArray": {"screen": {"width":
      160, "height": 90}, "observerDistance": 300, "observerHeight": 0, "angularScattering": "auto", "image": {"width":
      96, "height": 54}, "projectors": [)" +
                                projectors + "]}}",
                            "wall.json", "");
}

std::vector<float> directProjectorImages(const gpu_shared::ProjectorArrayParams& p, std::uint32_t w, std::uint32_t h) {
  std::vector<float> all;
  for (std::uint32_t k = 0; k < std::uint32_t(p.observer.w); ++k) {
    const std::vector<float> image = imageOf(w, h, [&](auto x, auto y, auto c) {
      glm::vec3 o, d;
      gpu_shared::projector_ray(p, x, y, k, glm::vec2(0.5f), o, d);
      return planeRadiance(glm::dvec3(o), glm::dvec3(d), c);
    });
    all.insert(all.end(), image.begin(), image.end());
  }
  return all;
}

std::vector<float> screenPinhole(const gpu_shared::ProjectorArrayParams& p, glm::dvec2 screen, glm::uvec2 size,
                                 glm::dvec3 eye) {
  const double scale = p.scale.x;
  const glm::dvec3 eyeWorld = worldPoint(p.localToWorld, scale, eye);
  return imageOf(size.x, size.y, [&](auto x, auto y, auto c) {
    const glm::dvec3 s(((x + 0.5) / size.x - 0.5) * screen.x, ((y + 0.5) / size.y - 0.5) * screen.y, 0.0);
    return pinholeRadiance(eyeWorld, worldPoint(p.localToWorld, scale, s), c);
  });
}

// Error budget: the eye sees a Gaussian blend of the few projectors nearest its direction (sigma about 3.3 degrees),
// each showing the plane 0.6 world units (27 display units) behind the screen from its own observer-line point:
// parallax differences of ~0.03 units, and bilinear sampling of 96x54 images (1.7 display units per pixel). The outer
// eyes (x = +-218) see only part of the screen at full brightness: S.x in [-30, 80] for x = 218. Measured: 47.5 dB
// straight ahead, 42.7 at x = +-97, 36.5 at x = +-218 (fewer projectors on one side of the blend); mirrored 11-19 dB.
TEST(SimulatedProjectorView, DirectRenderSeenFromAnEyeIsThePinholeViewFromThere) {
  const DisplayConfig config = projectorWall();
  const gpu_shared::ProjectorArrayParams p = makeProjectorArrayParams(config, Bounds3{});
  const std::uint32_t w = 96, h = 54;
  const glm::dvec2 screen(160.0, 90.0);
  const glm::uvec2 out(160, 90);
  const std::vector<float> images = directProjectorImages(p, w, h);
  const std::vector<glm::dvec3> eyes = projectorViewConeEyes(p, 5);
  ASSERT_EQ(eyes.size(), 5u);
  EXPECT_NEAR(eyes[2].x, 0.0, 1e-9);  // a symmetric array: the middle eye is straight ahead
  EXPECT_LT(eyes[0].x, eyes[4].x);
  for (const glm::dvec3& eye : eyes) {
    EXPECT_DOUBLE_EQ(eye.z, 300.0);
    const SimulatedView seen = simulateProjectorView(p, screen, w, h, images, eye, out, 2);
    EXPECT_GT(fullyLit(seen.rgba), std::fabs(eye.x) < 100.0 ? 0.95 : 0.6) << "eye x " << eye.x;
    const double right = psnr(seen.rgba, screenPinhole(p, screen, out, eye));
    const double wrong = psnr(seen.rgba, screenPinhole(p, screen, out, glm::dvec3(-eye.x, eye.y, eye.z)));
    EXPECT_GT(right, 33.0) << "eye x " << eye.x;
    if (std::fabs(eye.x) > 30.0) { EXPECT_GT(right, wrong + 6.0) << "eye x " << eye.x; }
  }
}

// One projector behind the screen centre whose homography lights the left half of the screen only. Right half: black,
// alpha 0. Left half: its colour, at a brightness set by how far its light misses the eye at (0, 0, 300): with a wide
// scattering lobe (3 rad) nearly full everywhere; with a narrow one (0.05 rad) the Gaussian of the miss dA, i.e. high
// only near the line from the projector through the screen to the eye (S.x ~ 0), nothing at the screen's left edge.
TEST(SimulatedProjectorView, CoverageAndBrightnessShowInAlpha) {
  for (const double scattering : {3.0, 0.05}) {
    const DisplayConfig config = parseDisplayConfig(R"({"name": "half", "model": "projector-array", "projectorArray": {
        "screen": {"width": 160, "height": 90}, "observerDistance": 300, "angularScattering": )" +
                                                        std::to_string(scattering) + R"(,
        "image": {"width": 48, "height": 27}, "projectors": [{"position": [0, 0, -180], "homography":
        [[1.6666666666666667, 0, -80], [0, 3.3333333333333335, -45], [0, 0, 1]]}]}})",
                                                    "half.json", "");
    const gpu_shared::ProjectorArrayParams p = makeProjectorArrayParams(config, Bounds3{});
    const std::vector<float> images(48 * 27 * 4, 0.7f);
    const SimulatedView seen = simulateProjectorView(p, {160, 90}, 48, 27, images, {0, 0, 300}, {32, 18}, 1);
    auto at = [&](std::uint32_t x, std::uint32_t row) { return &seen.rgba[(std::size_t(row) * 32 + x) * 4]; };
    for (std::uint32_t row = 0; row < 18; ++row) {
      for (std::uint32_t x = 0; x < 32; ++x) {
        if (x < 16) {
          EXPECT_NEAR(at(x, row)[0], 0.7f, 1e-6f) << x << "," << row;
          if (scattering > 1.0) { EXPECT_GT(at(x, row)[3], 0.9f) << x << "," << row; }
        } else {
          EXPECT_EQ(at(x, row)[3], 0.0f) << x << "," << row;
          EXPECT_EQ(at(x, row)[0], 0.0f) << x << "," << row;
        }
      }
    }
    if (scattering < 1.0) {
      for (std::uint32_t x : {0u, 8u, 15u}) {
        const double sx = ((x + 0.5) / 32.0 - 0.5) * 160.0;  // the projector at 0 lights sx toward atan(sx/180)
        const double dA = std::atan(sx / 180.0) - std::atan(-sx / 300.0);
        const double brightness = std::exp(-dA * dA * 1.11741 * 1.11741 / (scattering * scattering));
        EXPECT_NEAR(at(x, 9)[3], brightness, 1e-5) << "S.x " << sx;
      }
      EXPECT_GT(at(15, 9)[3], 0.75f);  // S.x = -2.5: 1.3 degrees off
      EXPECT_LT(at(0, 9)[3], 1e-6f);   // S.x = -77.5: 39 degrees off
    }
  }
  const DisplayConfig config = projectorWall();
  const gpu_shared::ProjectorArrayParams p = makeProjectorArrayParams(config, Bounds3{});
  const std::vector<float> images(37 * 48 * 27 * 4, 0.7f);
  EXPECT_NO_THROW(simulateProjectorView(p, {160, 90}, 48, 27, images, {0, 0, 300}, {32, 18}));
  EXPECT_THROW(simulateProjectorView(p, {160, 90}, 48, 26, images, {0, 0, 300}, {32, 18}), Error);
  EXPECT_THROW(simulateProjectorView(p, {160, 90}, 48, 27, images, {0, 0, -1}, {32, 18}), Error);
  EXPECT_THROW(simulateProjectorView(p, {160, 90}, 48, 27, images, {0, 0, 300}, {0, 18}), Error);
}

// ---- integral imaging ----------------------------------------------------------------------------------------------

// 240x160 LCD, 0.1 pitch, lenses of 1.0 (10 pixels) 3.0 in front of it: a +-9.5 degree viewing zone.
DisplayConfig integralPanel(const std::string& extra) {
  return parseDisplayConfig(R"({"name": "ii", "model": "integral", "integral": {"panelWidth": 240, "panelHeight":
      160, "pixelPitch": 0.1, "lensPitch": 1.0, "gap": 3.0, "viewerDistance": 300, "frontPlane": 100, )" +
                                extra + "}}",
                            "ii.json", "");
}

std::vector<float> directLcd(const gpu_shared::IntegralParams& p) {
  return imageOf(std::uint32_t(p.panel.x), std::uint32_t(p.panel.y), [&](auto x, auto y, auto c) {
    glm::vec3 o, d;
    gpu_shared::integral_ray(p, x, y, c, glm::vec2(0.5f), o, d);
    return planeRadiance(glm::dvec3(o), glm::dvec3(d), c);
  });
}

// The eye sees each lens as one colour: the scene along the line from the eye through the lens centre.
std::vector<float> lensPinhole(const DisplayConfig& config, const gpu_shared::IntegralParams& p, glm::dvec3 eye) {
  const IntegralReference reference(config, Bounds3{});
  const double scale = p.scale.x;
  const glm::dvec3 eyeWorld = worldPoint(p.localToWorld, scale, eye);
  return imageOf(std::uint32_t(p.panel.x), std::uint32_t(p.panel.y), [&](auto x, auto y, auto c) {
    const glm::dvec2 lens = reference.lensCentre(reference.pixelPosition(x, y, glm::dvec2(0.5)));
    return pinholeRadiance(eyeWorld, worldPoint(p.localToWorld, scale, glm::dvec3(lens, 0.0)), c);
  });
}

// Error budget: the LCD point the eye sees is read bilinearly between stripe subpixels 1/30 unit apart (slope steps
// of 0.011 over the gap); only where it falls on an elemental image's border does the blend mix two lenses' pixels,
// which the outer eyes (0.4 of the 0.5 half-width off centre) meet. Measured: 65-70 dB for x = 0, +-20, 35-36.5 dB
// for x = +-40; mirrored 17-23 dB.
TEST(SimulatedIntegralView, DirectRenderSeenFromAnEyeIsThePinholeViewThroughEachLens) {
  for (const std::string& grid : {std::string(R"("focalLength": 3.0, "sampling": "centre")"),
                                  std::string(R"("focalLength": 3.0, "sampling": "centre", "lensRotationDeg": 9,
                                                 "lensOffset": [0.31, -0.17])")}) {
    const DisplayConfig config = integralPanel(grid);
    const gpu_shared::IntegralParams p = makeIntegralParams(config, Bounds3{});
    const std::vector<float> lcd = directLcd(p);
    const std::vector<glm::dvec3> eyes = integralViewConeEyes(p, config.integral->viewerDistance, 5);
    ASSERT_EQ(eyes.size(), 5u);
    EXPECT_NEAR(eyes[0].x, -0.8 * 300.0 * 0.5 / 3.0, 1e-9);  // bin centre 0.1 of the +-1/6 slope range
    for (const glm::dvec3& eye : eyes) {
      const SimulatedView seen = simulateIntegralView(p, lcd, eye, 2);
      // The half lenses on the border (5 of 240 and 160 pixels on each side, 10 % of the area) show the eye points
      // past the LCD's edge.
      EXPECT_GT(fullyLit(seen.rgba), 0.85) << grid << ", eye x " << eye.x;
      const double right = psnr(seen.rgba, lensPinhole(config, p, eye));
      const double wrong = psnr(seen.rgba, lensPinhole(config, p, glm::dvec3(-eye.x, eye.y, eye.z)));
      EXPECT_GT(right, 32.0) << grid << ", eye x " << eye.x;
      if (std::fabs(eye.x) > 10.0) { EXPECT_GT(right, wrong + 6.0) << grid << ", eye x " << eye.x; }
    }
  }
}

// With the LCD in the lenses' focal plane (gap = f) every aperture point of a lens shows the eye the same LCD point,
// so aperture sampling sees what the lens centre sees (up to the eye's parallax across one lens, 1/300 rad).
TEST(SimulatedIntegralView, FocusedApertureSeesWhatTheLensCentreSees) {
  const DisplayConfig centre = integralPanel(R"("focalLength": 3.0, "sampling": "centre")");
  const DisplayConfig aperture = integralPanel(R"("focalLength": 3.0, "sampling": "aperture")");
  const gpu_shared::IntegralParams pc = makeIntegralParams(centre, Bounds3{});
  const gpu_shared::IntegralParams pa = makeIntegralParams(aperture, Bounds3{});
  const std::vector<float> lcd = directLcd(pc);
  const SimulatedView a = simulateIntegralView(pa, lcd, {12, -5, 300}, 2);
  const SimulatedView c = simulateIntegralView(pc, lcd, {12, -5, 300}, 2);
  EXPECT_GT(psnr(a.rgba, c.rgba), 60.0);  // measured 102 dB
  EXPECT_THROW(simulateIntegralView(pc, std::vector<float>(8, 0.0f), {0, 0, 300}), Error);
  EXPECT_THROW(simulateIntegralView(pc, lcd, {0, 0, 0}), Error);
}

}  // namespace
}  // namespace ht::test
