// Adaptive refinement (RenderSettings::refineSpp, gpu/adaptive_refinement.h, refine_select.comp) end to end: the
// targets the GPU refines are the ones the shared contrast function picks on the CPU from the base frame, a refined
// target takes the mean of all its samples (its base value and its value in a frame rendered at the refinement spp,
// weighted by their spp), every other target keeps its base value, and the frame is bit-identical from run to run.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/quilt_layout.h"
#include "camera_models/quilt_setup.h"
#include "common/error.h"
#include "gpu/adaptive_refinement.h"
#include "gpu_test_util.h"

namespace ht::test {
namespace {

// A small Portrait-calibrated panel (the Portrait's optics on 144 x 192 pixels): every refinement path in seconds.
gpu_shared::LenticularParams smallPortrait(const Scene& scene) {
  DisplayConfig display = builtinDisplay("portrait");
  display.calibration->screenW = kSanitized ? 72 : 144;
  display.calibration->screenH = kSanitized ? 96 : 192;
  return makeLenticularParams(display, scene.bounds());
}

gpu::RenderSettings withSpp(std::uint32_t spp, std::uint32_t refineSpp = 0, float contrast = 0.08f) {
  gpu::RenderSettings s;
  s.spp = spp;
  s.maxDepth = 2;
  s.refineSpp = refineSpp;
  s.refineContrast = contrast;
  return s;
}

// The CPU reference selection on a finished frame: the contrast of channel c of pixel (x, row) against the same
// channel of its 4 neighbours in the same view (rows of RenderResult::rgba run top-down, which the symmetric
// neighbourhood does not care about).
float cpuContrast(const gpu::RenderResult& f, std::uint32_t view, std::uint32_t x, std::uint32_t row, std::uint32_t c) {
  auto at = [&](std::uint32_t px, std::uint32_t py) {
    return f.rgba[((static_cast<size_t>(view) * f.height + py) * f.width + px) * 4 + c];
  };
  const std::uint32_t l = x > 0 ? x - 1 : x, r = x + 1 < f.width ? x + 1 : x;
  const std::uint32_t d = row > 0 ? row - 1 : row, u = row + 1 < f.height ? row + 1 : row;
  return gpu_shared::ht_refine_contrast(at(x, row), at(l, row), at(r, row), at(x, d), at(x, u));
}

struct SelectionCheck {
  size_t refined = 0, ambiguous = 0, wrong = 0, targets = 0;
};

// The value resolve.comp gives a refined target: the mean of its base samples and its refinement samples, from the
// frames rendered at those spp (whose values are their samples' sums divided by a power of two here: exact).
float refinedValue(float base, std::uint32_t baseSpp, float high, std::uint32_t refineSpp) {
  return (base * static_cast<float>(baseSpp) + high * static_cast<float>(refineSpp)) /
         static_cast<float>(baseSpp + refineSpp);
}

// Compares the adaptive frame with the base and the refinement-spp (high) frames target by target. subpixelTargets:
// one target per channel (lenticular); otherwise one RGB target per pixel, refined when any channel's contrast
// reaches it.
SelectionCheck checkSelection(const gpu::RenderResult& base, std::uint32_t baseSpp, const gpu::RenderResult& high,
                              std::uint32_t refineSpp, const gpu::RenderResult& adaptive, float threshold,
                              bool subpixelTargets) {
  SelectionCheck out;
  for (std::uint32_t view = 0; view < base.views; ++view) {
    for (std::uint32_t row = 0; row < base.height; ++row) {
      for (std::uint32_t x = 0; x < base.width; ++x) {
        const size_t pixel = (static_cast<size_t>(view) * base.height + row) * base.width + x;
        float contrast[3];
        for (std::uint32_t c = 0; c < 3; ++c) contrast[c] = cpuContrast(base, view, x, row, c);
        for (std::uint32_t t = 0; t < (subpixelTargets ? 3u : 1u); ++t) {
          const float k = subpixelTargets ? contrast[t] : std::max(contrast[0], std::max(contrast[1], contrast[2]));
          const std::uint32_t c0 = subpixelTargets ? t : 0, c1 = subpixelTargets ? t + 1 : 3;
          bool isBase = true, isRefined = true;
          for (std::uint32_t c = c0; c < c1; ++c) {
            const size_t at = pixel * 4 + c;
            isBase = isBase && adaptive.rgba[at] == base.rgba[at];
            isRefined =
                isRefined && adaptive.rgba[at] == refinedValue(base.rgba[at], baseSpp, high.rgba[at], refineSpp);
          }
          ++out.targets;
          const bool cpuRefines = k >= threshold;
          out.refined += cpuRefines;
          if (std::abs(k - threshold) < 1e-5f) {
            ++out.ambiguous;  // GLSL and C++ pow may round the last bit apart
            if (!isBase && !isRefined) ++out.wrong;
          } else if (cpuRefines ? !isRefined : !isBase) {
            ++out.wrong;
          }
        }
      }
    }
  }
  return out;
}

TEST(GpuRefinement, RefinedSubpixelsAreTheCpuSelectionAndTakeTheRefinedValues) {
  const Scene scene = loadScene("builtin:plain");  // diffuse only: a sample's value depends on its target alone
  const auto params = smallPortrait(scene);
  gpu::Renderer renderer(sharedContext(), scene);
  const float threshold = 0.08f;
  const auto base = renderer.renderLenticular(params, withSpp(1));
  const auto high = renderer.renderLenticular(params, withSpp(4));
  const auto adaptive = renderer.renderLenticular(params, withSpp(1, 4, threshold));
  const SelectionCheck check = checkSelection(base, 1, high, 4, adaptive, threshold, true);
  std::printf("targets %zu, refined on the GPU %llu, by the CPU reference %zu (%zu at the threshold)\n", check.targets,
              static_cast<unsigned long long>(adaptive.refinedTargets), check.refined, check.ambiguous);
  EXPECT_EQ(check.wrong, 0u);
  EXPECT_LE(std::abs(double(adaptive.refinedTargets) - double(check.refined)), double(check.ambiguous));
  EXPECT_GT(check.refined, check.targets / 100);                                  // the scene has edges ...
  EXPECT_LT(check.refined, check.targets / 2);                                    // ... and flat areas
  EXPECT_GE(adaptive.raysTraced, base.raysTraced + adaptive.refinedTargets * 4);  // + 4 primaries per refined target
}

// RGB pixel targets, each view's borders its own (no neighbour across views): the Portrait's quilt cameras.
TEST(GpuRefinement, RefinedPixelsOfMultiViewFramesAreTheCpuSelection) {
  const Scene scene = loadScene("builtin:plain");
  gpu::Renderer renderer(sharedContext(), scene);
  const DisplayConfig display = builtinDisplay("portrait");
  const QuiltLayout layout = makeQuiltLayout(8, 6, 8 * 24, 6 * 32, 0.75f);
  const auto params = makeQuiltParams(display, scene.bounds(), layout);
  const float threshold = 0.05f;
  const auto base = renderer.renderQuilt(params, withSpp(2));
  const auto high = renderer.renderQuilt(params, withSpp(8));
  const auto adaptive = renderer.renderQuilt(params, withSpp(2, 8, threshold));
  ASSERT_EQ(base.views, 48u);
  const SelectionCheck check = checkSelection(base, 2, high, 8, adaptive, threshold, false);
  EXPECT_EQ(check.wrong, 0u);
  EXPECT_LE(std::abs(double(adaptive.refinedTargets) - double(check.refined)), double(check.ambiguous));
  EXPECT_GT(check.refined, 0u);
  EXPECT_LT(check.refined, check.targets);
}

// The small Portrait panel over builtin:showcase (mirror, glass, textures, lights).
class GpuRefinementShowcase : public ::testing::Test {
 protected:
  gpu::RenderResult render(std::uint32_t spp, std::uint32_t refineSpp = 0, float contrast = 0.0f) {
    return renderer_.renderLenticular(params_, withSpp(spp, refineSpp, contrast));
  }
  Scene scene_ = loadScene("builtin:showcase");
  gpu_shared::LenticularParams params_ = smallPortrait(scene_);
  gpu::Renderer renderer_{sharedContext(), scene_};
};

// Threshold 0 refines every target: each takes the mean of its base sample and the samples of the frame at the
// refinement spp, bit for bit (glass too: the refined paths keep the full frame's path indices). A threshold above 1
// refines none: the base frame.
TEST_F(GpuRefinementShowcase, ThresholdsZeroAndAboveOneGiveAllSamplesMeanAndTheBaseFrame) {
  const auto base = render(1);
  const auto high = render(4);
  const auto all = render(1, 4, 0.0f);
  EXPECT_EQ(all.refinedTargets, std::uint64_t{high.width} * high.height * 3);
  ASSERT_EQ(all.rgba.size(), high.rgba.size());
  size_t differing = 0;
  for (size_t i = 0; i < all.rgba.size(); ++i) {
    if (i % 4 == 3) continue;  // alpha: 1 everywhere
    differing += all.rgba[i] != refinedValue(base.rgba[i], 1, high.rgba[i], 4);
  }
  EXPECT_EQ(differing, 0u);
  const auto none = render(1, 4, 1.01f);
  EXPECT_EQ(none.refinedTargets, 0u);
  EXPECT_EQ(none.rgba, base.rgba);
  EXPECT_EQ(none.raysTraced, base.raysTraced);
}

TEST_F(GpuRefinementShowcase, RefinedFramesAreBitIdenticalFromRunToRun) {
  const auto a = render(1, 4, 0.05f);
  const auto b = render(1, 4, 0.05f);
  EXPECT_GT(a.refinedTargets, 0u);
  EXPECT_EQ(a.refinedTargets, b.refinedTargets);
  EXPECT_EQ(a.rgba, b.rgba);
}

TEST(GpuRefinement, BadRefinementSettingsAreRefusedBeforeAnyWork) {
  const Scene scene = loadScene("builtin:plain");
  const auto params = smallPortrait(scene);
  gpu::Renderer renderer(sharedContext(), scene);
  for (float bad : {-0.1f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    EXPECT_THROW(renderer.renderLenticular(params, withSpp(1, 4, bad)), GpuError) << bad;
  }
  EXPECT_THROW(renderer.renderLenticular(params, withSpp(1, 5000, 0.1f)), GpuError);
}

}  // namespace
}  // namespace ht::test
