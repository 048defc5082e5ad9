// file_sink_failure_test.cpp - FileSink when the disk says no: ENOSPC/EDQUOT (injected through FileOps, at write
// and at fsync) and EFBIG (a real RLIMIT_FSIZE with SIGXFSZ ignored, as holotraced runs) are DiskFull ->
// RESOURCE_EXHAUSTED; other errors stay IoError -> INTERNAL; in every case no temp file remains and an existing
// file of the same name keeps its old contents.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <cerrno>
#include <fstream>
#include <iterator>

#include "common/error.h"
#include "server/file_sink.h"
#include "server/status_mapping.h"
#include "tests/server/server_fixture.h"

namespace ht::server::test {
namespace {

std::string readSinkFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// write() that stores `okBytes` for real, then fails with `err` (a disk that fills up mid-file).
FileOps failingWrite(std::size_t okBytes, int err) {
  auto left = std::make_shared<std::size_t>(okBytes);
  FileOps ops;
  ops.write = [left, err](int fd, const void* data, std::size_t size) -> ssize_t {
    if (*left == 0) {
      errno = err;
      return -1;
    }
    const ssize_t n = ::write(fd, data, std::min(size, *left));
    if (n > 0) *left -= static_cast<std::size_t>(n);
    return n;
  };
  return ops;
}

grpc::StatusCode codeOf(const std::function<void()>& f) {
  try {
    f();
  } catch (...) { return statusFromException(std::current_exception()).error_code(); }
  return grpc::StatusCode::OK;
}

class FileSinkFailureTest : public ::testing::Test {
 protected:
  void SetUp() override { writeText(root() / "frame.png", "old contents"); }
  std::filesystem::path root() const { return dir_.path / "out"; }
  const std::vector<std::uint8_t> bytes_ = std::vector<std::uint8_t>(200'000, 9);

 private:
  TempDir dir_;
};

TEST_F(FileSinkFailureTest, EnospcMidWriteIsDiskFullAndLeavesNothingPartial) {
  FileSink sink(root(), failingWrite(70'000, ENOSPC));
  EXPECT_THROW(sink.writeFile("frame.png", bytes_), DiskFull);
  EXPECT_THROW(sink.writeFile("new.png", bytes_), DiskFull);
  EXPECT_EQ(entries(root()), std::vector<std::string>{"frame.png"});  // no temp file, no new.png
  EXPECT_EQ(readSinkFile(root() / "frame.png"), "old contents");
  EXPECT_EQ(codeOf([&] { sink.writeFile("x.png", bytes_); }), grpc::StatusCode::RESOURCE_EXHAUSTED);
}

TEST_F(FileSinkFailureTest, EdquotAtFsyncIsDiskFull) {
  FileOps ops;
  ops.fsync = [](int) {
    errno = EDQUOT;
    return -1;
  };
  FileSink sink(root(), ops);
  try {
    sink.writeFile("frame.png", bytes_);
    FAIL() << "a failed fsync was ignored";
  } catch (const DiskFull& e) { EXPECT_NE(std::string(e.what()).find("frame.png"), std::string::npos) << e.what(); }
  EXPECT_EQ(entries(root()), std::vector<std::string>{"frame.png"});
  EXPECT_EQ(readSinkFile(root() / "frame.png"), "old contents");
}

// A frame's files as one set (Capture): the disk fills up in the third file; none of the three appears, the old file
// of the first name keeps its contents, no temp file remains.
TEST_F(FileSinkFailureTest, FullDiskInTheMiddleOfAFileSetLeavesNoneOfIt) {
  FileSink sink(root(), failingWrite(450'000, ENOSPC));  // two complete 200 kB files, then the third fails
  const std::vector<frame_io::FrameFile> files = {
      {"frame.png", bytes_}, {"frame.json", bytes_}, {"frame_v02.png", bytes_}};
  EXPECT_THROW(sink.writeFiles(files), DiskFull);
  EXPECT_EQ(entries(root()), std::vector<std::string>{"frame.png"});
  EXPECT_EQ(readSinkFile(root() / "frame.png"), "old contents");
}

TEST_F(FileSinkFailureTest, OtherWriteErrorsAreInternalAndAlsoLeaveNothing) {
  FileSink sink(root(), failingWrite(0, EIO));
  EXPECT_EQ(codeOf([&] { sink.writeFile("new.png", bytes_); }), grpc::StatusCode::INTERNAL);
  EXPECT_EQ(entries(root()), std::vector<std::string>{"frame.png"});
}

// The kernel's own path: over RLIMIT_FSIZE write() fails with EFBIG when SIGXFSZ is ignored (setrlimit(2)); holotraced
// ignores SIGXFSZ (server/main.cpp). Each gtest case runs in its own process under ctest, the limit is restored.
TEST_F(FileSinkFailureTest, FileSizeLimitIsDiskFullNotACrash) {
  rlimit before{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &before), 0);
  const auto oldHandler = ::signal(SIGXFSZ, SIG_IGN);
  rlimit small = before;
  small.rlim_cur = 64 * 1024;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  FileSink sink(root());
  grpc::StatusCode big = grpc::StatusCode::OK, fits = grpc::StatusCode::UNKNOWN;
  big = codeOf([&] { sink.writeFile("big.png", bytes_); });  // 200 kB > 64 KiB
  fits = codeOf([&] { sink.writeFile("small.png", std::vector<std::uint8_t>(1000, 1)); });
  ::setrlimit(RLIMIT_FSIZE, &before);
  ::signal(SIGXFSZ, oldHandler);
  EXPECT_EQ(big, grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(fits, grpc::StatusCode::OK);
  EXPECT_EQ(entries(root()), (std::vector<std::string>{"frame.png", "small.png"}));
}

}  // namespace
}  // namespace ht::server::test
