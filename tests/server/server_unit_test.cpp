// server_unit_test.cpp - the daemon's edges without a GPU: client names and paths, the confined FileSink,
// config parsing and listen-address rules.
#include <gtest/gtest.h>

#include <fstream>

#include "common/error.h"
#include "server/daemon_config.h"
#include "server/file_sink.h"
#include "server/listen_address.h"
#include "server/path_rules.h"
#include "server/status_mapping.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

TEST(PathRulesTest, FileNameComponents) {
  EXPECT_NO_THROW(checkFileNameComponent("name", "take_1.v2-a"));
  EXPECT_THROW(checkFileNameComponent("name", ".."), AccessDenied);
  EXPECT_THROW(checkFileNameComponent("name", "a/b"), AccessDenied);
  EXPECT_THROW(checkFileNameComponent("name", "/abs"), AccessDenied);
  EXPECT_THROW(checkFileNameComponent("name", ".hidden"), BadRequest);
  EXPECT_THROW(checkFileNameComponent("name", ""), BadRequest);
  EXPECT_THROW(checkFileNameComponent("name", "sp ace"), BadRequest);
  EXPECT_THROW(checkFileNameComponent("name", std::string(101, 'a')), BadRequest);
}

TEST(PathRulesTest, RelativePathsStayBeneathTheRoot) {
  EXPECT_EQ(resolveBeneath("/r", "path", "a/./b.obj"), std::filesystem::path("/r/a/b.obj"));
  EXPECT_THROW(resolveBeneath("/r", "path", "../x"), AccessDenied);
  EXPECT_THROW(resolveBeneath("/r", "path", "a/../../x"), AccessDenied);
  EXPECT_THROW(resolveBeneath("/r", "path", "/etc/passwd"), AccessDenied);
  EXPECT_THROW(resolveBeneath("/r", "path", ""), BadRequest);
  EXPECT_THROW(resolveBeneath("/r", "path", std::string("a\0b", 3)), BadRequest);
}

std::string readAll(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FileSinkTest, WritesCompleteFilesOnlyBeneathTheRootItOpened) {
  TempDir dir;
  FileSink sink(dir.path / "out");
  const std::vector<std::uint8_t> bytes(100'000, 7);
  sink.writeFile("a.bin", bytes);
  EXPECT_EQ(readAll(dir.path / "out" / "a.bin").size(), bytes.size());
  // Swapping the root for a symlink after opening does not redirect writes: the sink holds the directory fd.
  std::filesystem::rename(dir.path / "out", dir.path / "moved");
  std::filesystem::create_directories(dir.path / "elsewhere");
  std::filesystem::create_symlink(dir.path / "elsewhere", dir.path / "out");
  sink.writeFile("b.bin", bytes);
  EXPECT_TRUE(std::filesystem::exists(dir.path / "moved" / "b.bin"));
  EXPECT_FALSE(std::filesystem::exists(dir.path / "elsewhere" / "b.bin"));
  for (const auto& e : std::filesystem::directory_iterator(dir.path / "moved")) {
    EXPECT_NE(e.path().filename().string().front(), '.') << "temp file left: " << e.path();
  }
}

TEST(FileSinkTest, AFileSetAppearsWhole) {
  TempDir dir;
  FileSink sink(dir.path / "out");
  sink.writeFiles({{{"q.png", {1, 2, 3}}, {"q.json", {'{', '}'}}}});
  EXPECT_EQ(readAll(dir.path / "out" / "q.png"), std::string("\x01\x02\x03"));
  EXPECT_EQ(readAll(dir.path / "out" / "q.json"), "{}");
}

// Every server error is an ht::Error and maps to its status by type; the derived DiskFull wins over its base IoError.
TEST(StatusMappingTest, EveryErrorTypeHasItsCode) {
  using grpc::StatusCode;
  EXPECT_EQ(statusCodeOf(AccessDenied("a")), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(statusCodeOf(BadRequest("field", "b")), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(statusCodeOf(LimitExceeded("c")), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(statusCodeOf(DiskFull("d")), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(statusCodeOf(UnknownDisplay("e")), StatusCode::NOT_FOUND);
  EXPECT_EQ(statusCodeOf(UnknownScene("f")), StatusCode::NOT_FOUND);
  EXPECT_EQ(statusCodeOf(ShuttingDown("g")), StatusCode::UNAVAILABLE);
  EXPECT_EQ(statusCodeOf(ClientGone("h")), StatusCode::CANCELLED);
  EXPECT_EQ(statusCodeOf(ConfigError("f.json", "spp", "0", ">= 1")), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(statusCodeOf(SceneError("s.obj", "bad")), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(statusCodeOf(UsageError("layout")), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(statusCodeOf(GpuError("lost")), StatusCode::INTERNAL);
  EXPECT_EQ(statusCodeOf(IoError("io")), StatusCode::INTERNAL);
  EXPECT_EQ(statusCodeOf(Error("other")), StatusCode::INTERNAL);
  EXPECT_EQ(BadRequest("render.spp", "too big").field(), "render.spp");
  const grpc::Status gpu = statusFromException(std::make_exception_ptr(GpuError("device lost")));
  EXPECT_EQ(gpu.error_message(), "GPU: device lost");
  const grpc::Status disk = statusFromException(std::make_exception_ptr(DiskFull("output disk full")));
  EXPECT_EQ(disk.error_code(), StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(disk.error_message(), "output disk full");
}

TEST(DaemonConfigTest, ParsesPathsAndLimits) {
  const DaemonConfig c = parseDaemonConfig(
      R"({"scene_root": "s", "output_root": "/o", "limits": {"max_clients": 3, "max_scene_bytes": 1000}})", "t.json",
      "/base");
  EXPECT_EQ(c.sceneRoot, std::filesystem::path("/base/s"));
  EXPECT_EQ(c.outputRoot, std::filesystem::path("/o"));
  EXPECT_EQ(c.limits.maxClients, 3u);
  EXPECT_EQ(c.limits.maxSceneBytes, 1000u);
  EXPECT_EQ(c.limits.maxSpp, Limits{}.maxSpp);
  ASSERT_EQ(c.listen.size(), 1u);
  EXPECT_EQ(c.listen[0].rfind("unix:/", 0), 0u);
}

TEST(DaemonConfigTest, RejectsBadValuesNamingTheField) {
  try {
    parseDaemonConfig(R"({"scene_root": "s", "output_root": "o", "limits": {"max_clients": -1}})", "t.json", "/");
    FAIL() << "accepted a negative limit";
  } catch (const ConfigError& e) { EXPECT_EQ(e.field(), "limits.max_clients"); }
  EXPECT_THROW(parseDaemonConfig(R"({"output_root": "o"})", "t.json", "/"), ConfigError);
  EXPECT_THROW(parseDaemonConfig("{not json", "t.json", "/"), ConfigError);
}

TEST(ListenAddressTest, OnlyUnixSocketsAndLoopback) {
  EXPECT_NO_THROW(checkListenAddress("c", "unix:/run/x.sock"));
  EXPECT_NO_THROW(checkListenAddress("c", "127.0.0.1:5000"));
  EXPECT_NO_THROW(checkListenAddress("c", "[::1]:5000"));
  EXPECT_THROW(checkListenAddress("c", "0.0.0.0:5000"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "unix:relative.sock"), ConfigError);
  EXPECT_THROW(checkListenAddress("c", "unix-abstract:x"), ConfigError);
}

}  // namespace
}  // namespace ht::server::test
