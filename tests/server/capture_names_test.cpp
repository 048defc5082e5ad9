// capture_names_test.cpp - issue 14 items 6 and 10: a Capture name is exclusive (an existing name is ALREADY_EXISTS
// unless overwrite, a running capture's name too), overwrite leaves no mix of old and new frames, a cancelled
// capture writes no further file, and a directory in the way is named (FAILED_PRECONDITION, not INTERNAL).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "server/capture_output.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

using grpc::StatusCode;
using ::testing::HasSubstr;

class CaptureNamesTest : public InProcessDaemonTest<CaptureNamesTest> {
 protected:
  v1::CaptureRequest request(const std::string& name, std::uint32_t frames, bool overwrite = false) const {
    v1::CaptureRequest r;
    *r.mutable_render() = tinyRequest(sceneId_);
    r.set_name(name);
    r.set_frames(frames);
    r.set_overwrite(overwrite);
    return r;
  }
  grpc::Status run(const v1::CaptureRequest& r) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    auto reader = stub_->Capture(&context, r);
    v1::CaptureProgress progress;
    while (reader->Read(&progress)) {}
    return reader->Finish();
  }
  std::vector<std::string> filesOf(const std::string& name) const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(files_->outputRoot())) {
      const std::string file = entry.path().filename().string();
      if (isCaptureFileOf(name, file) || file.rfind("." + name + "_f", 0) == 0) names.push_back(file);
    }
    std::sort(names.begin(), names.end());
    return names;
  }
};

TEST(CaptureFileNamesTest, OnlyTheNamesACaptureWrites) {
  EXPECT_TRUE(isCaptureFileOf("take", "take_f0000.png"));
  EXPECT_TRUE(isCaptureFileOf("take", "take_f0012_qs8x6a0.75.json"));
  EXPECT_TRUE(isCaptureFileOf("take", "take_f0001_v03.png"));
  EXPECT_FALSE(isCaptureFileOf("take", "take_f0001_f0000.png"));  // capture "take_f0001"
  EXPECT_FALSE(isCaptureFileOf("take", "take2_f0000.png"));
  EXPECT_FALSE(isCaptureFileOf("take", "take_f.png"));
}

// A second, shorter capture under an existing name left a mix of old and new files; now it is refused and the old
// files stay as they were, or with overwrite the name holds exactly the new capture.
TEST_F(CaptureNamesTest, AnExistingNameIsRefusedUnlessOverwrite) {
  ASSERT_TRUE(run(request("dup", 3)).ok());
  const std::vector<std::string> first = filesOf("dup");
  ASSERT_EQ(first, (std::vector<std::string>{"dup_f0000.png", "dup_f0001.png", "dup_f0002.png"}));
  const auto before = std::filesystem::last_write_time(files_->outputRoot() / "dup_f0000.png");

  const grpc::Status again = run(request("dup", 1));
  EXPECT_EQ(again.error_code(), StatusCode::ALREADY_EXISTS) << again.error_message();
  EXPECT_THAT(again.error_message(), HasSubstr("overwrite"));
  EXPECT_EQ(filesOf("dup"), first);
  EXPECT_EQ(std::filesystem::last_write_time(files_->outputRoot() / "dup_f0000.png"), before);

  ASSERT_TRUE(run(request("dup", 1, true)).ok());
  EXPECT_EQ(filesOf("dup"), (std::vector<std::string>{"dup_f0000.png"}));
  EXPECT_TRUE(isCompletePng(files_->outputRoot() / "dup_f0000.png"));
}

// Two concurrent same-name captures both reported OK while one's files were overwritten; now the second is refused
// while the first runs, overwrite or not, and the name is free again afterwards.
TEST_F(CaptureNamesTest, ARunningCapturesNameIsExclusive) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto reader = stub_->Capture(&context, request("busy", 50));
  v1::CaptureProgress progress;
  ASSERT_TRUE(reader->Read(&progress));  // the first capture holds the name now
  const grpc::Status second = run(request("busy", 1, true));
  EXPECT_EQ(second.error_code(), StatusCode::ALREADY_EXISTS) << second.error_message();
  EXPECT_THAT(second.error_message(), HasSubstr("running capture"));
  while (reader->Read(&progress)) {}
  ASSERT_TRUE(reader->Finish().ok());
  EXPECT_EQ(filesOf("busy").size(), 50u);
  EXPECT_TRUE(run(request("busy", 1, true)).ok());
}

// After a cancel the frame being rendered is dropped: no file appears once the client has cancelled.
TEST_F(CaptureNamesTest, ACancelledCaptureWritesNoFurtherFile) {
  v1::CaptureRequest slow = request("cancelled", 50);
  slow.mutable_render()->set_spp(16);  // renders take long against the write, so the cancel lands mid-render
  grpc::ClientContext context;
  auto reader = stub_->Capture(&context, slow);
  v1::CaptureProgress progress;
  ASSERT_TRUE(reader->Read(&progress));
  context.TryCancel();
  EXPECT_EQ(reader->Finish().error_code(), StatusCode::CANCELLED);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  v1::StatusResponse status;
  do {  // until the daemon's handler has returned
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    grpc::ClientContext statusContext;
    ASSERT_TRUE(stub_->Status(&statusContext, v1::StatusRequest(), &status).ok());
  } while (status.active_streams() != 0 && std::chrono::steady_clock::now() < deadline);
  // Frame 0 was reported, so it is complete; frame 1 was rendering when the cancel came and must not appear.
  EXPECT_EQ(filesOf("cancelled"), (std::vector<std::string>{"cancelled_f0000.png"}));
}

// A directory where a capture file must go was INTERNAL; it is an existing name (ALREADY_EXISTS), and with
// overwrite a FAILED_PRECONDITION naming the directory. Nothing is written either way.
TEST_F(CaptureNamesTest, ADirectoryInTheWayIsNamed) {
  std::filesystem::create_directory(files_->outputRoot() / "dirq_f0000.png");
  const grpc::Status taken = run(request("dirq", 1));
  EXPECT_EQ(taken.error_code(), StatusCode::ALREADY_EXISTS) << taken.error_message();
  const grpc::Status blocked = run(request("dirq", 1, true));
  EXPECT_EQ(blocked.error_code(), StatusCode::FAILED_PRECONDITION) << blocked.error_message();
  EXPECT_THAT(blocked.error_message(), HasSubstr("dirq_f0000.png"));
  EXPECT_THAT(blocked.error_message(), HasSubstr("directory"));
  EXPECT_TRUE(std::filesystem::is_directory(files_->outputRoot() / "dirq_f0000.png"));
  EXPECT_EQ(filesOf("dirq"), (std::vector<std::string>{"dirq_f0000.png"}));
}

}  // namespace
}  // namespace ht::server::test
