// disk_full_test.cpp - a Capture into an output root that really fills up: a tmpfs of a few pages mounted for the
// test (needs root and mount(2); skipped with the reason otherwise). The capture ends with RESOURCE_EXHAUSTED, every
// file left is a complete PNG, no temp file remains, and the daemon keeps serving; with space freed it captures again.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>

#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

// A tmpfs of `size` on `dir` for the object's lifetime (lazily detached at the end, even if files are open).
class TinyTmpfs {
 public:
  TinyTmpfs(const std::filesystem::path& dir, const std::string& size) : dir_(dir) {
    std::filesystem::create_directories(dir);
    if (::geteuid() != 0) {
      error_ = "not root (mount(2) needs CAP_SYS_ADMIN)";
    } else if (::mount("tmpfs", dir.c_str(), "tmpfs", MS_NOSUID | MS_NODEV, ("size=" + size).c_str()) != 0) {
      error_ = std::string("mount -t tmpfs failed: ") + std::strerror(errno);
    }
  }
  ~TinyTmpfs() {
    if (error_.empty()) ::umount2(dir_.c_str(), MNT_DETACH);
  }
  const std::string& error() const { return error_; }

 private:
  std::filesystem::path dir_;
  std::string error_;
};

struct CaptureResult {
  grpc::Status status;
  std::vector<std::string> files;
};

CaptureResult capture(v1::Holotrace::Stub& stub, const std::string& sceneId, const std::string& name,
                      std::uint32_t frames) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::CaptureRequest request;
  *request.mutable_render() = tinyRequest(sceneId);
  request.set_name(name);
  request.set_frames(frames);
  auto reader = stub.Capture(&context, request);
  CaptureResult result;
  v1::CaptureProgress progress;
  while (reader->Read(&progress)) result.files.push_back(progress.file());
  result.status = reader->Finish();
  return result;
}

TEST(DiskFullTest, CaptureIntoAFullDiskIsResourceExhaustedAndLeavesOnlyCompleteFiles) {
  DaemonFiles files;
  TinyTmpfs tmpfs(files.outputRoot(), "64k");  // 16 pages; a 96x64 PNG of the plain scene is several KiB
  if (!tmpfs.error().empty()) GTEST_SKIP() << tmpfs.error();
  {
    Daemon daemon(files.config(), std::cerr);
    daemon.start();
    auto stub = connect(files.socketAddress());
    v1::SceneHandle scene;
    ASSERT_TRUE(loadScene(*stub, "builtin:plain", &scene).ok());

    const CaptureResult full = capture(*stub, scene.scene_id(), "fill", 50);
    EXPECT_EQ(full.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED) << full.status.error_message();
    EXPECT_NE(full.status.error_message().find("disk full"), std::string::npos) << full.status.error_message();
    EXPECT_LT(full.files.size(), 50u);
    std::size_t left = 0;
    for (const auto& entry : std::filesystem::directory_iterator(files.outputRoot())) {
      const std::string name = entry.path().filename().string();
      EXPECT_NE(name.front(), '.') << "temp file left: " << name;
      EXPECT_TRUE(isCompletePng(entry.path())) << name;
      EXPECT_NE(std::find(full.files.begin(), full.files.end(), name), full.files.end()) << "unreported " << name;
      ++left;
    }
    EXPECT_EQ(left, full.files.size());  // every reported file is there, nothing else

    ASSERT_TRUE(renderOne(*stub, tinyRequest(scene.scene_id())).ok());  // the daemon still serves
    for (const auto& name : full.files) std::filesystem::remove(files.outputRoot() / name);
    const CaptureResult again = capture(*stub, scene.scene_id(), "again", 1);
    EXPECT_TRUE(again.status.ok()) << again.status.error_message();
    daemon.shutdown();
  }
}

}  // namespace
}  // namespace ht::server::test
