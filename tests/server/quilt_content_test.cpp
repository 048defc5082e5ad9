// quilt_content_test.cpp - a quilt image as daemon content (server/quilt_content.h): LoadScene of a `_qs`-named PNG
// under the scene root gives a session whose RenderFrame is the quilt interleaved for the display (byte for byte what
// `holotrace interleave` computes, frame_io/quilt_file.h), Capture writes it, StreamFrames streams it, and quilts
// that cannot fit the requested display or requests that make no sense for a quilt fail with the value named.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/image_limits.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"
#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
#include "frame_io/quilt_file.h"
#include "frame_io/quilt_metadata.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

class QuiltContentTest : public InProcessDaemonTest<QuiltContentTest> {
 protected:
  // The PNG bytes of a 96x48 quilt (4x3 tiles of 24x16) whose pixels vary with view and position, with `attributes`.
  static std::vector<std::uint8_t> quiltPng(const frame_io::ImageAttributes& attributes = {}, std::uint32_t w = 96,
                                            std::uint32_t h = 48) {
    std::vector<float> rgba(std::size_t(w) * h * 4, 1.0f);
    for (std::uint32_t y = 0; y < h; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        for (std::uint32_t c = 0; c < 3; ++c) {
          rgba[(std::size_t(y) * w + x) * 4 + c] = float((x * 7 + y * 3 + c * 50) % 97) / 96.0f;
        }
      }
    }
    return frame_io::encodeImage({w, h, rgba}, frame_io::ImageFormat::Png8Srgb, attributes);
  }

  // The quilt written below the scene root as `name`.
  std::filesystem::path writeQuilt(const std::string& name) {
    const frame_io::OutputFile file{files_->sceneRoot() / name, quiltPng()};
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
  for (const Case& c : {Case{"wide_qs4x3a1.777.png", "tiny", false, "quilt aspect"},
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
  // A quilt without a layout in its name or metadata is refused when it is loaded, naming the file.
  const grpc::Status noLayout = loadScene(*stub_, "holiday.png");
  EXPECT_EQ(noLayout.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << noLayout.error_message();
  EXPECT_NE(noLayout.error_message().find("holiday.png: field 'quilt name'"), std::string::npos)
      << noLayout.error_message();
  // The quilt cameras of a quilt make no sense (refused by the request's size limit or as a quilt already).
  v1::SceneHandle handle;
  ASSERT_TRUE(loadScene(*stub_, "ok_qs4x3a1.5.png", &handle).ok());
  v1::RenderRequest quiltOfQuilt = tinyRequest(handle.scene_id());
  quiltOfQuilt.set_quilt(true);
  EXPECT_FALSE(renderOne(*stub_, quiltOfQuilt).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(sceneId_)).ok());  // the daemon is still fine
}

std::string asString(const std::vector<std::uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

// Issue 18 item 2: UploadScene takes quilt images too; an uploaded quilt is the same content as the loaded file.
TEST_F(QuiltContentTest, UploadedQuiltRendersAsTheLoadedFile) {
  writeQuilt("upload_qs4x3a1.5.png");
  v1::SceneHandle loaded, uploaded;
  ASSERT_TRUE(loadScene(*stub_, "upload_qs4x3a1.5.png", &loaded).ok());
  const grpc::Status status = uploadScene(*stub_, "upload_qs4x3a1.5.png", asString(quiltPng()), &uploaded);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_EQ(uploaded.triangles(), 0u);
  EXPECT_TRUE(uploaded.reused());  // same bytes, same name: the loaded content, interleaved panels included
  ReceivedFrame fromFile, fromUpload;
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(loaded.scene_id()), &fromFile).ok());
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(uploaded.scene_id()), &fromUpload).ok());
  EXPECT_EQ(fromUpload.bytes, fromFile.bytes);

  // The layout from holotrace's metadata when the name has no tag (a renamed holotrace quilt), here as an EXR.
  const DisplayConfig tiny = parseDisplayConfig(tinyDisplayJson(), "tiny.json", "");
  const std::string meta = frame_io::quiltMetadataJson(tiny, makeQuiltLayout(4, 3, 96, 48, 1.5));
  const frame_io::ImageFile png = frame_io::decodeImage(quiltPng(), "q.png");
  const std::vector<std::uint8_t> exr = frame_io::encodeImage(
      {png.width, png.height, png.rgba}, frame_io::ImageFormat::ExrFloat, {{"ImageDescription", meta}});
  v1::SceneHandle renamed;
  ASSERT_TRUE(uploadScene(*stub_, "renamed.exr", asString(exr), &renamed).ok());
  ReceivedFrame fromExr;
  ASSERT_TRUE(renderOne(*stub_, tinyRequest(renamed.scene_id()), &fromExr).ok());
  EXPECT_EQ(fromExr.bytes, fromFile.bytes);
}

TEST_F(QuiltContentTest, UploadedQuiltsWithoutAUsableLayoutFailNamingTheFieldAndTheFix) {
  const DisplayConfig tiny = parseDisplayConfig(tinyDisplayJson(), "tiny.json", "");
  const std::string meta8x6 = frame_io::quiltMetadataJson(tiny, makeQuiltLayout(8, 6, 96, 48, 1.5));
  struct Case {
    std::string name, bytes, message;
  };
  const std::uint32_t tooWide = kMaxImageSide + 1;
  for (const Case& c : {
           Case{"holiday.png", asString(quiltPng()), "info.file_name: holiday.png: field 'quilt name'"},
           Case{"take_qs4x3a1.5.png", asString(quiltPng({{"ImageDescription", meta8x6}})),
                "field 'quilt name' = 4x3: the file's embedded metadata says 8x6 views; rename the file"},
           Case{"dust_qs64x24a1.5.png", asString(quiltPng()), "field 'quilt size' = 96x48"},
           Case{"junk_qs4x3a1.5.png", "not a png", "junk_qs4x3a1.5.png: not a quilt image holotrace can read"},
           Case{"huge_qs4x3a1.5.png", asString(quiltPng({}, tooWide, 3)), "size 32769x3 (expected 1..32768 per side)"},
           Case{"notes.txt", "text", "or .png or .exr (a quilt image"},
       }) {
    const grpc::Status status = uploadScene(*stub_, c.name, c.bytes);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << c.name << ": " << status.error_message();
    EXPECT_NE(status.error_message().find(c.message), std::string::npos) << c.name << ": " << status.error_message();
  }
  // A quilt for another panel uploads (the display is not known yet) and is refused by the frame that asks for one.
  v1::SceneHandle wide;
  ASSERT_TRUE(uploadScene(*stub_, "wide_qs4x3a1.777.png", asString(quiltPng()), &wide).ok());
  const grpc::Status status = renderOne(*stub_, tinyRequest(wide.scene_id()));
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();
  EXPECT_NE(status.error_message().find("field 'quilt aspect' = 1.777"), std::string::npos) << status.error_message();
}

}  // namespace
}  // namespace ht::server::test
