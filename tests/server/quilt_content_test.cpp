// quilt_content_test.cpp - a quilt image as daemon content (server/quilt_content.h): LoadScene of a `_qs`-named PNG
// under the scene root gives a session whose RenderFrame is the quilt interleaved for the display (byte for byte what
// `holotrace interleave` computes, frame_io/quilt_file.h), Capture writes it, StreamFrames streams it, and quilts
// that cannot fit the requested display or requests that make no sense for a quilt fail with the value named.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"
#include "frame_io/pixel_encoding.h"
#include "frame_io/quilt_file.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

class QuiltContentTest : public InProcessDaemonTest<QuiltContentTest> {
 protected:
  // A 4x3 quilt of 24x16 tiles whose pixels vary with view and position, written below the scene root.
  std::filesystem::path writeQuilt(const std::string& name) {
    const std::uint32_t w = 96, h = 48;
    std::vector<float> rgba(std::size_t(w) * h * 4, 1.0f);
    for (std::uint32_t y = 0; y < h; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        for (std::uint32_t c = 0; c < 3; ++c) {
          rgba[(std::size_t(y) * w + x) * 4 + c] = float((x * 7 + y * 3 + c * 50) % 97) / 96.0f;
        }
      }
    }
    const frame_io::OutputFile file{files_->sceneRoot() / name,
                                    frame_io::encodeImage({w, h, rgba}, frame_io::ImageFormat::Png8Srgb)};
    frame_io::writeFilesAtomically({&file, 1});
    return file.path;
  }
};

TEST_F(QuiltContentTest, RenderFrameIsTheQuiltInterleavedForTheDisplay) {
  const auto path = writeQuilt("take_qs4x3a1.5.png");
  v1::SceneHandle handle;
  ASSERT_TRUE(loadScene(*stub_, "take_qs4x3a1.5.png", &handle).ok());
  EXPECT_EQ(handle.triangles(), 0u);

  ReceivedFrame frame;
  const grpc::Status status = renderOne(*stub_, tinyRequest(handle.scene_id(), v1::PIXEL_FORMAT_RGBA8), &frame);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(frame.header.width(), kTinyWidth);
  ASSERT_EQ(frame.header.height(), kTinyHeight);
  const DisplayConfig tiny = parseDisplayConfig(tinyDisplayJson(), "tiny.json", "");
  const frame_io::InterleavedQuilt want = frame_io::interleaveQuiltFile(path, tiny, {}, QuiltViewFilter::VendorLerp, 1);
  ASSERT_EQ(frame.bytes.size(), want.rgba.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < want.rgba.size(); ++i) {
    const std::uint8_t expected = i % 4 == 3 ? 255 : frame_io::srgbEncode8(want.rgba[i]);
    differ += frame.bytes[i] != expected;
  }
  EXPECT_EQ(differ, 0u);

  // The same frame through Capture, and as a stream.
  std::vector<std::string> files;
  ASSERT_TRUE(captureFrame(*stub_, "quiltshot", tinyRequest(handle.scene_id(), v1::PIXEL_FORMAT_RGBA8),
                           v1::CAPTURE_FORMAT_PNG, v1::CAPTURE_LAYOUT_AUTO, files)
                  .ok());
  ASSERT_EQ(files, std::vector<std::string>{"quiltshot_f0000.png"});
  EXPECT_TRUE(isCompletePng(files_->outputRoot() / files[0]));
}

TEST_F(QuiltContentTest, QuiltsThatCannotFitTheRequestFailNamingTheValue) {
  writeQuilt("wide_qs4x3a1.777.png");
  writeQuilt("holiday.png");
  writeQuilt("ok_qs4x3a1.5.png");
  struct Case {
    std::string file, display;
    bool quiltPath;
    std::string message;
  };
  for (const Case& c :
       {Case{"wide_qs4x3a1.777.png", "tiny", false, "quilt aspect"}, Case{"holiday.png", "tiny", false, "quilt name"},
        Case{"ok_qs4x3a1.5.png", "wall", false, "model"}}) {
    v1::SceneHandle handle;
    ASSERT_TRUE(loadScene(*stub_, c.file, &handle).ok()) << c.file;
    v1::RenderRequest request = tinyRequest(handle.scene_id());
    request.set_display_id(c.display);
    request.set_quilt(c.quiltPath);
    const grpc::Status status = renderOne(*stub_, request);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.file << ": " << status.error_message();
    EXPECT_NE(status.error_message().find(c.message), std::string::npos) << status.error_message();
  }
  // The quilt cameras of a quilt make no sense (refused by the request's size limit or as a quilt already).
  v1::SceneHandle handle;
  ASSERT_TRUE(loadScene(*stub_, "ok_qs4x3a1.5.png", &handle).ok());
  v1::RenderRequest quiltOfQuilt = tinyRequest(handle.scene_id());
  quiltOfQuilt.set_quilt(true);
  EXPECT_FALSE(renderOne(*stub_, quiltOfQuilt).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_)).ok());  // the daemon is still fine
}

}  // namespace
}  // namespace ht::server::test
