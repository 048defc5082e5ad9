// file_sink.h - writes complete files beneath the output root, never elsewhere and never partially: the root is
// opened once; each file is created as a hidden temp name with openat2(RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS)
// (fallback: openat + O_NOFOLLOW on kernels without openat2, ENOSYS), written, fsynced and renamed into place
// (docs/SERVICE.md §6 "Output confinement"; Linux include/uapi/linux/openat2.h).
#pragma once
#include <sys/types.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>

#include "frame_io/frame_package.h"
#include "server/errors.h"

namespace ht::server {

// The calls a FileSink makes on its open temp file (return -1 and set errno on failure, like the system calls).
// Tests substitute them to inject what a real disk gives only when full: ENOSPC from write, EDQUOT from fsync.
struct FileOps {
  std::function<ssize_t(int fd, const void* data, std::size_t size)> write = ::write;
  std::function<int(int fd)> fsync = ::fsync;
};

class FileSink {
 public:
  // Creates the root if missing; throws IoError.
  explicit FileSink(const std::filesystem::path& root, FileOps ops = {});
  ~FileSink();
  FileSink(const FileSink&) = delete;
  FileSink& operator=(const FileSink&) = delete;

  // `name` must be one validated path component. Throws DiskFull (ENOSPC, EDQUOT, EFBIG) or IoError; either way
  // the temp file is removed and `name` is untouched.
  void writeFile(const std::string& name, std::span<const std::uint8_t> bytes);

  // The files of one frame (frame_io::packageFrame) as a set: every file is written and fsynced under its temp name
  // before the first rename, so a full disk or any write error leaves none of them (and names untouched). If a rename
  // fails, the files of the set already renamed are removed too: the set is there whole or not at all. Throws as
  // writeFile.
  void writeFiles(std::span<const frame_io::FrameFile> files);

 private:
  int openTemp(const std::string& tempName);
  int writeAll(int fd, std::span<const std::uint8_t> bytes);                    // 0 or the errno
  int writeTemp(const std::string& temp, std::span<const std::uint8_t> bytes);  // 0 or the errno; fd closed
  FileOps ops_;
  int rootFd_ = -1;
};

}  // namespace ht::server
