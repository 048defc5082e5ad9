// file_sink.h - writes complete files beneath the output root, never elsewhere and never partially: the root is
// opened once; each file is created as a hidden temp name with openat2(RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS)
// (fallback: openat + O_NOFOLLOW on kernels without openat2, ENOSYS), written, fsynced and renamed into place
// (docs/service.md §6 "Output confinement"; Linux include/uapi/linux/openat2.h).
#pragma once
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>

namespace ht::server {

class FileSink {
 public:
  explicit FileSink(const std::filesystem::path& root);  // creates the root if missing; throws IoError
  ~FileSink();
  FileSink(const FileSink&) = delete;
  FileSink& operator=(const FileSink&) = delete;

  // `name` must be one validated path component. Throws IoError (ENOSPC/EDQUOT -> DiskFull).
  void writeFile(const std::string& name, std::span<const std::uint8_t> bytes);

 private:
  int openTemp(const std::string& tempName);
  int rootFd_ = -1;
};

// The disk (or quota) is full: the file was not written, nothing partial remains.
class DiskFull : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ht::server
