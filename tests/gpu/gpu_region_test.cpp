// Sub-renders (RenderSettings::region): a band of rows or a range of views renders exactly the bits the whole frame
// has at those pixels, also through glass (whose random Fresnel choice is keyed by the frame-wide target, not by the
// path's place in its chunk), so a cluster can cut a frame into work units and assemble it bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "camera_models/display_config.h"
#include "camera_models/lenticular_params.h"
#include "common/error.h"
#include "gpu/display_camera.h"
#include "gpu_test_util.h"

namespace ht::test {
namespace {

gpu::RenderSettings regionSettings(std::uint32_t spp, gpu::RenderRegion region = {}) {
  gpu::RenderSettings s;
  s.spp = spp;
  s.maxDepth = 3;
  s.seed = 5;
  s.region = region;
  return s;
}

// The floats of rows [rowFirst, rowFirst + rows) of views [viewFirst, + views) of a whole frame.
std::vector<float> cut(const gpu::RenderResult& whole, std::uint32_t viewFirst, std::uint32_t views,
                       std::uint32_t rowFirst, std::uint32_t rows) {
  std::vector<float> part;
  const std::size_t rowFloats = std::size_t{whole.width} * 4;
  for (std::uint32_t v = viewFirst; v < viewFirst + views; ++v) {
    const float* view = whole.rgba.data() + std::size_t{v} * whole.height * rowFloats;
    part.insert(part.end(), view + rowFirst * rowFloats, view + (rowFirst + rows) * rowFloats);
  }
  return part;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

class GpuRegion : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new Scene(loadScene("builtin:showcase")); }  // glass, mirror, lights
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }
  // The Portrait's lenticular model on a 40 x 30 panel.
  static gpu::FrameCamera smallPanel() {
    DisplayConfig display = builtinDisplay("portrait");
    display.calibration->screenW = 40;
    display.calibration->screenH = 30;
    return makeLenticularParams(display, scene_->bounds());
  }
  static Scene* scene_;
};
Scene* GpuRegion::scene_ = nullptr;

TEST_F(GpuRegion, RowBandsOfALenticularPanelAreTheWholeFramesRows) {
  const gpu::FrameCamera camera = smallPanel();
  gpu::Renderer renderer(sharedContext(), *scene_);
  const gpu::RenderResult whole = renderer.render(camera, regionSettings(2));
  ASSERT_EQ(whole.height, 30u);
  for (const auto& [first, rows] : {std::pair{0u, 7u}, {7u, 1u}, {8u, 13u}, {21u, 9u}}) {
    const gpu::RenderResult band = renderer.render(camera, regionSettings(2, {0, 0, first, rows}));
    EXPECT_EQ(band.width, 40u);
    EXPECT_EQ(band.height, rows);
    EXPECT_TRUE(sameBits(band.rgba, cut(whole, 0, 1, first, rows))) << "rows " << first << " + " << rows;
  }
}

TEST_F(GpuRegion, ViewRangesAndBandsOfAProjectorArrayAreTheWholeFramesPixels) {
  const DisplayConfig display = smallProjectorArray();
  const gpu::FrameCamera camera = gpu::makeDisplayCamera(display, scene_->bounds()).camera;
  gpu::Renderer renderer(sharedContext(), *scene_);
  const gpu::RenderResult whole = renderer.render(camera, regionSettings(2));
  ASSERT_EQ(whole.views, 4u);
  const gpu::RenderResult views = renderer.render(camera, regionSettings(2, {1, 2, 0, 0}));
  EXPECT_EQ(views.views, 2u);
  EXPECT_TRUE(sameBits(views.rgba, cut(whole, 1, 2, 0, 12)));
  const gpu::RenderResult corner = renderer.render(camera, regionSettings(2, {3, 0, 5, 4}));
  EXPECT_EQ(corner.views, 1u);
  EXPECT_TRUE(sameBits(corner.rgba, cut(whole, 3, 1, 5, 4)));
}

TEST_F(GpuRegion, RegionsOutsideTheFrameAndRefinedBandsAreRefused) {
  DisplayConfig display = builtinDisplay("portrait");
  display.calibration->screenW = 16;
  display.calibration->screenH = 8;
  const gpu::FrameCamera camera = makeLenticularParams(display, scene_->bounds());
  gpu::Renderer renderer(sharedContext(), *scene_);
  EXPECT_THROW(renderer.render(camera, regionSettings(1, {0, 0, 8, 0})), GpuError);
  EXPECT_THROW(renderer.render(camera, regionSettings(1, {0, 0, 2, 7})), GpuError);
  EXPECT_THROW(renderer.render(camera, regionSettings(1, {1, 0, 0, 0})), GpuError);
  gpu::RenderSettings refined = regionSettings(1, {0, 0, 0, 4});
  refined.refineSpp = 2;
  EXPECT_THROW(renderer.render(camera, refined), GpuError);
  refined.region = {};
  EXPECT_NO_THROW(renderer.render(camera, refined));
}

// Renderer::recycle: a recycled buffer of the frame's size is written whole (none of its old values survive) and
// used instead of a new one, for whole frames and for bands of rows; one too small or more than twice too large is
// not.
TEST_F(GpuRegion, RecycledFrameBuffersAreReusedAndOverwrittenWhole) {
  const gpu::FrameCamera camera = smallPanel();
  gpu::Renderer renderer(sharedContext(), *scene_);
  const gpu::RenderResult fresh = renderer.render(camera, regionSettings(2));
  const gpu::RenderRegion band{0, 0, 4, 20};  // 20 of 30 rows
  const std::vector<float> bandFresh = renderer.render(camera, regionSettings(2, band)).rgba;

  std::vector<float> junk(fresh.rgba.size(), std::numeric_limits<float>::quiet_NaN());
  const float* junkData = junk.data();
  renderer.recycle(std::move(junk));
  gpu::RenderResult again = renderer.render(camera, regionSettings(2));
  EXPECT_EQ(again.rgba.data(), junkData) << "the recycled buffer was not used";
  EXPECT_TRUE(sameBits(again.rgba, fresh.rgba));

  // The same buffer for a band of rows (more than half its size): used, and the band's values only.
  ASSERT_GT(bandFresh.size() * 2, again.rgba.size());
  const float* againData = again.rgba.data();
  renderer.recycle(std::move(again.rgba));
  const gpu::RenderResult bandAgain = renderer.render(camera, regionSettings(2, band));
  EXPECT_EQ(bandAgain.rgba.data(), againData);
  EXPECT_TRUE(sameBits(bandAgain.rgba, bandFresh));

  // Too small, and more than twice too large: left alone.
  renderer.recycle(std::vector<float>(fresh.rgba.size() - 4, 1.0f));
  renderer.recycle(std::vector<float>(fresh.rgba.size() * 2 + 8, 1.0f));
  const gpu::RenderResult third = renderer.render(camera, regionSettings(2));
  EXPECT_TRUE(sameBits(third.rgba, fresh.rgba));
}

}  // namespace
}  // namespace ht::test
