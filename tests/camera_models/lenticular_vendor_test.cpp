// The shared float model against the VENDOR SHADER formula, re-implemented here from docs/OPTICS.md §3 (not from
// lenticular_model.h): holoplaycore.js `GetSubpixelViews` (§3.1) and the Gen3 cell variant `GetCellForPixel` /
// `GetPixelShift` (§3.2), on the real calibrations of docs/OPTICS.md §1.1, at every subpixel of each panel.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "camera_models/lenticular_model.h"
#include "camera_models/lenticular_params.h"
#include "camera_test_support.h"

namespace ht {
namespace {

using test::loadFixture;

// holoplaycore.js dist/holoplaycore.js, Shader(cfg) / GetSubpixelViews, in the scalar type T (float = what a GLSL
// shader computes with float uniforms, double = the formula itself):
//   view = (u + c*subp + v*tilt)*pitch - center            (classic)
//   view = ((u + offX/W) + (v + offY/H)*tilt)*pitch - center (Gen3 cells, no subp term)
//   view = 1 - fract(view)                                  (before the clamp to [0.00001, 0.999999])
template <class T>
struct VendorShader {
  T pitch, tilt, subp, center, width, height;
  const LookingGlassCalibration* calibration;

  static T fract(T a) { return a - std::floor(a); }

  // holoplaycore.js GetCellForPixel with xPos = int(u*W), yPos = int(v*H).
  int cell(int xPos, int yPos) const {
    int mode = calibration->cellPatternMode;
    int c = 0;
    if (mode == 1) c = (xPos % 2 == yPos % 2) ? 0 : 1;
    if (mode == 2) c = xPos % 2;
    if (mode == 3) c = (yPos + (xPos % 2) * 2) % 4;
    if (mode == 4) c = yPos % 2;
    return c % static_cast<int>(calibration->subpixelCells.size());
  }

  T phi(int x, int y, int c) const {
    const T u = (T(x) + T(0.5)) / width, v = (T(y) + T(0.5)) / height;
    if (calibration->cellPatternMode == 0) return (u + T(c) * subp + v * tilt) * pitch - center;
    const glm::dvec2 offset = calibration->subpixelCells[cell(x, y)].offset(static_cast<std::uint32_t>(c));
    const T du = T(offset.x) / width, dv = T(offset.y) / height;
    return ((u + du) + (v + dv) * tilt) * pitch - center;
  }

  T unclampedView(int x, int y, int c) const { return T(1) - fract(phi(x, y, c)); }
  static int index(T view, int views) {
    view = std::clamp(view, T(0.00001), T(0.999999));
    return static_cast<int>(view * T(views));
  }
};

template <class T>
VendorShader<T> vendorShader(const LookingGlassCalibration& c) {
  const LenticularShaderValues v = lenticularShaderValues(c);
  return {T(v.pitch), T(v.tilt), T(v.subp), T(v.center), T(c.screenW), T(c.screenH), &c};
}

struct VendorComparison {
  double maxVsDouble = 0.0;  // |t_model - t_vendor(double)| on the phase circle
  double maxVsFloat = 0.0;   // |t_model - t_vendor(float)|
  double maxFloatVendorError = 0.0;
  long indexMismatches = 0;  // view index differs although the phase is not within 1e-5 of a bin edge
  long nearEdge = 0;
  long samples = 0;
};

VendorComparison compareWithVendor(const DisplayConfig& config, int views, std::uint32_t rowStride) {
  const LookingGlassCalibration& calibration = *config.calibration;
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const VendorShader<double> exact = vendorShader<double>(calibration);
  const VendorShader<float> single = vendorShader<float>(calibration);
  VendorComparison result;
  for (std::uint32_t y = 0; y < calibration.screenH; y += rowStride) {
    for (std::uint32_t x = 0; x < calibration.screenW; ++x) {
      for (std::uint32_t c = 0; c < 3; ++c) {
        const double model = gpu_shared::lenticular_view_phase(p, x, y, c, glm::vec2(0.5f));
        const double vendor = exact.unclampedView(int(x), int(y), int(c));
        const double vendorFloat = single.unclampedView(int(x), int(y), int(c));
        result.maxVsDouble = std::max(result.maxVsDouble, std::fabs(test::phaseDifference(model, vendor)));
        result.maxVsFloat = std::max(result.maxVsFloat, std::fabs(test::phaseDifference(model, vendorFloat)));
        result.maxFloatVendorError =
            std::max(result.maxFloatVendorError, std::fabs(test::phaseDifference(vendorFloat, vendor)));
        const double scaled = vendor * views;
        const bool nearBinEdge = std::fabs(scaled - std::round(scaled)) < 1e-5 * views;
        const int modelIndex = static_cast<int>(std::floor(model * views));
        if (nearBinEdge) {
          ++result.nearEdge;
        } else if (modelIndex != VendorShader<double>::index(vendor, views)) {
          ++result.indexMismatches;
        }
        ++result.samples;
      }
    }
  }
  std::printf(
      "[ %s ] %ld subpixels, N=%d: max |dt| vs vendor double %.3g, vs vendor float %.3g "
      "(vendor float vs double %.3g); %ld within 1e-5 of a bin edge, %ld index mismatches elsewhere\n",
      config.name.c_str(), result.samples, views, result.maxVsDouble, result.maxVsFloat, result.maxFloatVendorError,
      result.nearEdge, result.indexMismatches);
  return result;
}

// Bound on the model's phase error: splitting makes the integer part exact, the remaining float terms are below ~4
// in magnitude, so a handful of roundings of <= 2^-23 each: ~1e-6 with margin (measured: ~2e-7).
constexpr double kModelPhaseBound = 1e-6;

// A float vendor shader rounds phi ~ pitch_s ~ 250-370 to 2^-16..2^-15: its error is a few times 1e-5, our model's
// distance to it is bounded by the same.
constexpr double kFloatVendorBound = 1e-4;

// rowStride 1 = every subpixel of the panel; 2 = every other row (keeps the suite fast on 4K panels).
void expectMatchesVendor(const DisplayConfig& config, int views, std::uint32_t rowStride = 1) {
  VendorComparison r = compareWithVendor(config, views, rowStride);
  EXPECT_EQ(r.indexMismatches, 0);
  EXPECT_LT(r.maxVsDouble, kModelPhaseBound);
  EXPECT_LT(r.maxVsFloat, kFloatVendorBound);
  EXPECT_LT(r.nearEdge, r.samples / 100);  // the exclusion is a thin set
}

TEST(CameraModelsVendor, PortraitPr56EverySubpixel) {
  expectMatchesVendor(loadFixture("portrait_pr56_visual.json"), 48);
}

TEST(CameraModelsVendor, PortraitIssue3EverySubpixel) {
  expectMatchesVendor(loadFixture("portrait_issue3_visual.json"), 48);
}

TEST(CameraModelsVendor, Gen1OriginalEveryOtherRow) {
  expectMatchesVendor(loadFixture("gen1_8.9_original_visual.json"), 45, 2);
}

TEST(CameraModelsVendor, GoTemplateEveryOtherRow) {
  expectMatchesVendor(loadFixture("go_template_visual.json"), 66, 2);
}

TEST(CameraModelsVendor, Gen3LandscapeCellsEveryOtherRow) {
  expectMatchesVendor(loadFixture("gen3_16_landscape_visual.json"), 49, 2);
}

TEST(CameraModelsVendor, Gen3PortraitCellsEveryOtherRow) {
  expectMatchesVendor(loadFixture("gen3_16_portrait_lowercase_visual.json"), 66, 2);
}

// flipSubp (BGR): output R takes the phase of subpixel 2 and B of subpixel 0 (HoloPlayCore ri/bi, docs/OPTICS.md §3.1).
TEST(CameraModelsVendor, FlipSubpSwapsRedAndBlue) {
  DisplayConfig config = loadFixture("portrait_pr56_visual.json");
  DisplayConfig bgr = config;
  bgr.calibration->flipSubp = true;
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const gpu_shared::LenticularParams q = makeLenticularParams(bgr, test::testBounds());
  EXPECT_EQ(panelLayout(bgr).bgr, true);
  for (std::uint32_t y = 0; y < 2048; y += 97) {
    for (std::uint32_t x = 0; x < 1536; x += 89) {
      const glm::vec2 xi(0.25f, 0.75f);
      EXPECT_EQ(gpu_shared::lenticular_view_phase(q, x, y, 0, xi), gpu_shared::lenticular_view_phase(p, x, y, 2, xi));
      EXPECT_EQ(gpu_shared::lenticular_view_phase(q, x, y, 1, xi), gpu_shared::lenticular_view_phase(p, x, y, 1, xi));
      EXPECT_EQ(gpu_shared::lenticular_view_phase(q, x, y, 2, xi), gpu_shared::lenticular_view_phase(p, x, y, 0, xi));
    }
  }
}

// invView 0 follows holoplay.js v0.2.3: z = (1-invView)*z + invView*(1-z), i.e. t = fract(phi).
TEST(CameraModelsVendor, InvViewZeroIsHoloplayJsOrder) {
  DisplayConfig config = loadFixture("portrait_pr56_visual.json");
  DisplayConfig forward = config;
  forward.calibration->invView = false;
  const gpu_shared::LenticularParams p = makeLenticularParams(forward, test::testBounds());
  const VendorShader<double> exact = vendorShader<double>(*forward.calibration);
  double maxError = 0.0;
  for (std::uint32_t y = 0; y < 2048; y += 7) {
    for (std::uint32_t x = 0; x < 1536; x += 5) {
      for (std::uint32_t c = 0; c < 3; ++c) {
        const double phi = exact.phi(int(x), int(y), int(c));
        const double t = gpu_shared::lenticular_view_phase(p, x, y, c, glm::vec2(0.5f));
        maxError = std::max(maxError, std::fabs(test::phaseDifference(t, phi - std::floor(phi))));
      }
    }
  }
  EXPECT_LT(maxError, kModelPhaseBound);
}

// The footprint is 1/3 px wide: across it the phase changes by pitch_s*subp (docs/OPTICS.md §9 M2, w_t), decreasing
// with invView. Along y the footprint spans one pixel: tilt*pitch_s/H.
TEST(CameraModelsVendor, FootprintPhaseWidth) {
  DisplayConfig config = loadFixture("portrait_pr56_visual.json");
  const gpu_shared::LenticularParams p = makeLenticularParams(config, test::testBounds());
  const LenticularShaderValues v = lenticularShaderValues(*config.calibration);
  const double widthX = v.pitch * v.subp, widthY = v.tilt * v.pitch / 2048.0;
  for (std::uint32_t x : {0u, 700u, 1535u}) {
    for (std::uint32_t y : {0u, 1000u, 2047u}) {
      const double left = gpu_shared::lenticular_view_phase(p, x, y, 1, glm::vec2(0.0f, 0.5f));
      const double right = gpu_shared::lenticular_view_phase(p, x, y, 1, glm::vec2(1.0f, 0.5f));
      const double bottom = gpu_shared::lenticular_view_phase(p, x, y, 1, glm::vec2(0.5f, 0.0f));
      const double top = gpu_shared::lenticular_view_phase(p, x, y, 1, glm::vec2(0.5f, 1.0f));
      EXPECT_NEAR(test::phaseDifference(right, left), -widthX, kModelPhaseBound);
      EXPECT_NEAR(test::phaseDifference(top, bottom), -widthY, kModelPhaseBound);
    }
  }
}

}  // namespace
}  // namespace ht
