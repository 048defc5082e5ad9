// daemon_process_test.cpp - the real holotraced binary: SIGHUP reloads displays; SIGTERM during a capture ends
// the capture at a frame boundary, leaves only complete files, removes the socket and exits 0.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <regex>
#include <thread>

#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

using Clock = std::chrono::steady_clock;

class DaemonProcess {
 public:
  explicit DaemonProcess(const std::filesystem::path& config) {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::execl(HOLOTRACED_EXE, HOLOTRACED_EXE, "--config", config.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~DaemonProcess() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  void signal(int sig) const { ::kill(pid_, sig); }
  // Exit status, or -1 if it did not exit within `timeout`.
  int waitExit(std::chrono::seconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
};

struct ProcessFixture {
  DaemonFiles files;
  std::filesystem::path socket = files.dir.path / "run" / "d.sock";
  std::filesystem::path configFile = files.dir.path / "holotraced.json";
  ProcessFixture() {
    writeText(configFile, R"({"displays_dir": "displays", "scene_root": "scenes", "output_root": "out",
      "listen": ["unix:)" + socket.string() + R"("], "limits": {"max_capture_frames": 500}})");
  }
  std::unique_ptr<v1::Holotrace::Stub> waitReady() const {
    const auto deadline = Clock::now() + std::chrono::seconds(30);
    while (Clock::now() < deadline) {
      if (std::filesystem::exists(socket)) {
        auto stub = connect("unix:" + socket.string());
        grpc::ClientContext context;
        context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(2));
        v1::StatusResponse status;
        if (stub->Status(&context, {}, &status).ok()) return stub;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return nullptr;
  }
};

TEST(DaemonProcessTest, SighupReloadsDisplayConfigs) {
  ProcessFixture f;
  DaemonProcess daemon(f.configFile);
  auto stub = f.waitReady();
  ASSERT_TRUE(stub);
  writeText(f.files.dir.path / "displays" / "added.json", tinyDisplayJson());
  daemon.signal(SIGHUP);
  bool found = false;
  for (int i = 0; i < 100 && !found; ++i) {
    grpc::ClientContext context;
    v1::GetDisplayRequest request;
    request.set_display_id("added");
    v1::Display display;
    found = stub->GetDisplay(&context, request, &display).ok();
    if (!found) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(found);
  const auto stopStart = Clock::now();
  daemon.signal(SIGTERM);  // with the client's connection still open
  EXPECT_EQ(daemon.waitExit(std::chrono::seconds(20)), 0);
  EXPECT_LT(Clock::now() - stopStart, std::chrono::seconds(3));  // an idle open connection does not delay exit
}

TEST(DaemonProcessTest, SigtermDuringCaptureLeavesOnlyCompleteFiles) {
  ProcessFixture f;
  DaemonProcess daemon(f.configFile);
  auto stub = f.waitReady();
  ASSERT_TRUE(stub);
  v1::SceneHandle handle;
  ASSERT_TRUE(loadScene(*stub, "builtin:plain", &handle).ok());

  grpc::ClientContext context;
  v1::CaptureRequest request;
  *request.mutable_render() = tinyRequest(handle.scene_id());
  request.set_name("run");
  request.set_frames(400);
  auto reader = stub->Capture(&context, request);
  v1::CaptureProgress progress;
  ASSERT_TRUE(reader->Read(&progress));
  ASSERT_TRUE(reader->Read(&progress));
  daemon.signal(SIGTERM);
  std::uint32_t done = progress.frames_done();
  while (reader->Read(&progress)) done = progress.frames_done();
  const grpc::Status status = reader->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::UNAVAILABLE) << status.error_message();
  EXPECT_LT(done, 400u);
  EXPECT_EQ(daemon.waitExit(std::chrono::seconds(20)), 0);

  const std::regex complete("run_f[0-9]{4}\\.png");
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(f.files.outputRoot())) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(std::regex_match(name, complete)) << "unexpected file " << name;
    EXPECT_TRUE(isCompletePng(entry.path())) << name;
    ++files;
  }
  EXPECT_GE(files, 2u);
  EXPECT_FALSE(std::filesystem::exists(f.socket));
}

}  // namespace
}  // namespace ht::server::test
