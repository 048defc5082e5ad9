// daemon_hardening_test.cpp - holotraced under abuse (issue 14): a second daemon on the same address is refused and
// the first keeps serving; a frame rate below the documented range is refused, not overflowed.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "common/error.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

using grpc::StatusCode;

bool daemonAnswers(const std::string& address) {
  auto stub = connect(address);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  v1::StatusResponse status;
  return stub->Status(&context, {}, &status).ok();
}

std::string secondDaemonError(const DaemonConfig& config) {
  try {
    Daemon second(config, std::cerr);
    second.start();
  } catch (const IoError& e) { return e.what(); }
  return "";
}

TEST(ListenOwnershipTest, SecondDaemonOnTheSameSocketIsRefusedAndTheFirstKeepsServing) {
  DaemonFiles files;
  Daemon first(files.config(), std::cerr);
  first.start();
  ASSERT_TRUE(daemonAnswers(files.socketAddress()));
  const std::string error = secondDaemonError(files.config());
  EXPECT_NE(error.find("another holotraced"), std::string::npos) << error;
  EXPECT_NE(error.find(std::to_string(::getpid())), std::string::npos) << error;     // the holder's pid
  EXPECT_TRUE(std::filesystem::exists(files.dir.path / "run" / "holotraced.sock"));  // not unlinked by the loser
  EXPECT_TRUE(daemonAnswers(files.socketAddress()));
  first.shutdown(std::chrono::milliseconds(0));
  EXPECT_FALSE(std::filesystem::exists(files.dir.path / "run" / "holotraced.sock"));
  // The address is free again once its owner stopped.
  Daemon third(files.config(), std::cerr);
  third.start();
  EXPECT_TRUE(daemonAnswers(files.socketAddress()));
}

// A loopback port nobody listens on now.
int freeLoopbackPort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t length = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &length);
  ::close(fd);
  return ntohs(addr.sin_port);
}

TEST(ListenOwnershipTest, SecondDaemonOnTheSameTcpPortIsRefusedNotShared) {
  DaemonFiles files;
  DaemonConfig config = files.config();
  const std::string address = "127.0.0.1:" + std::to_string(freeLoopbackPort());
  config.listen = {address};
  Daemon first(config, std::cerr);
  first.start();
  ASSERT_TRUE(daemonAnswers(address));
  const std::string error = secondDaemonError(config);
  EXPECT_NE(error.find("in use"), std::string::npos) << error;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(daemonAnswers(address));
}

// Item 1: every `holotrace client` call loads a scene and exits. Sessions used to pile up under a hidden cap of 256,
// after which every load was RESOURCE_EXHAUSTED until restart. 600 short-lived clients (own channel each) load and
// render (every 10th renders, to stay fast) and never unload; all succeed (the 10,000-cycle form with RSS is the soak
// program, bench/soak_main.cpp).
class ShortLivedClientsTest : public InProcessDaemonTest<ShortLivedClientsTest> {};

TEST_F(ShortLivedClientsTest, SixHundredLoadRenderCyclesWithoutUnloadKeepWorking) {
  for (int cycle = 0; cycle < 600; ++cycle) {
    auto client = connect(files_->socketAddress());
    v1::SceneHandle handle;
    const grpc::Status loaded = loadScene(*client, cycle % 2 ? "builtin:plain" : "cube.obj", &handle);
    ASSERT_TRUE(loaded.ok()) << "cycle " << cycle << ": " << loaded.error_message();
    if (cycle % 10 == 9) {
      const grpc::Status rendered = renderOne(*client, tinyRequest(handle.scene_id()));
      ASSERT_TRUE(rendered.ok()) << "cycle " << cycle << ": " << rendered.error_message();
    }
  }
}

class StreamRateTest : public InProcessDaemonTest<StreamRateTest> {};

grpc::Status streamAt(v1::Holotrace::Stub& stub, const std::string& sceneId, double fps, int* frames) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(20));
  v1::StreamRequest request;
  request.set_mode(v1::STREAM_MODE_INDEPENDENT);  // continuous frames (progressive converges and goes quiet)
  *request.mutable_render() = tinyRequest(sceneId);
  request.set_frames_per_second(fps);
  auto reader = stub.StreamFrames(&context, request);
  ReceivedFrame frame;
  *frames = 0;
  while (*frames < 5 && readFrame(*reader, frame)) ++*frames;
  if (*frames == 5) context.TryCancel();  // else the stream ended with the daemon's status
  while (readFrame(*reader, frame)) {}
  return reader->Finish();
}

TEST_F(StreamRateTest, RatesOutsideTheRangeAreRefusedBeforeAnyFrame) {
  for (double fps : {1e-11, 1e-300, 0.0005, -1.0, 121.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    int frames = -1;
    const grpc::Status status = streamAt(*stub_, sceneId_, fps, &frames);
    EXPECT_EQ(status.error_code(), StatusCode::INVALID_ARGUMENT) << fps;
    EXPECT_NE(status.error_message().find("frames_per_second"), std::string::npos) << status.error_message();
    EXPECT_EQ(frames, 0) << fps;
  }
  int frames = 0;
  EXPECT_EQ(streamAt(*stub_, sceneId_, 120.0, &frames).error_code(), StatusCode::CANCELLED);
  EXPECT_EQ(frames, 5);
}

}  // namespace
}  // namespace ht::server::test
