// atomic_output_file.cpp - see atomic_output_file.h.
#include "frame_io/atomic_output_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "common/error.h"

namespace ht::frame_io {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void throwIo(const fs::path& path, const std::string& what, const std::string& reason) {
  throw IoError("cannot write '" + path.string() + "': " + what + ": " + reason);
}

fs::path directoryOf(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

void createParentDirectory(const fs::path& target) {
  const fs::path parent = directoryOf(target);
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throwIo(target, "cannot create directory '" + parent.string() + "'", ec.message());
  if (!fs::is_directory(parent, ec)) throwIo(target, "'" + parent.string() + "' is not a directory", "check the path");
}

// mkstemp-created temporary "<dir>/.<name>.tmp-XXXXXX" with ordinary 0644 permissions.
fs::path createTempFile(const fs::path& target) {
  // Built with appends: GCC 12 -O3 reports a false -Wrestrict for `"." + std::string` (GCC bug 105329).
  std::string hiddenName = ".";
  hiddenName += target.filename().string();
  hiddenName += ".tmp-XXXXXX";
  const std::string name = (directoryOf(target) / hiddenName).string();
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  const int fd = ::mkstemp(buffer.data());
  if (fd < 0)
    throwIo(target, "cannot create a temporary file in '" + directoryOf(target).string() + "'", std::strerror(errno));
  ::fchmod(fd, 0644);
  ::close(fd);
  return fs::path(buffer.data());
}

}  // namespace

void prepareOutputDirectory(const fs::path& target) {
  createParentDirectory(target);
  const fs::path directory = directoryOf(target);
  if (::access(directory.c_str(), W_OK | X_OK) != 0) {
    throwIo(target, "directory '" + directory.string() + "' is not writable", std::strerror(errno));
  }
}

AtomicOutputFile::AtomicOutputFile(fs::path target) : target_(std::move(target)) {
  if (target_.empty()) throw IoError("cannot write an output file: the path is empty (give a file name)");
  if (target_.filename().empty()) throwIo(target_, "the path names a directory", "add a file name");
  createParentDirectory(target_);
  temp_ = createTempFile(target_);
}

AtomicOutputFile::~AtomicOutputFile() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove(temp_, ignored);
}

void AtomicOutputFile::commit() {
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  committed_ = true;  // from here on the temporary file is either renamed or removed below
  if (ec) {
    const std::string reason = ec.message();
    std::error_code ignored;
    fs::remove(temp_, ignored);
    throwIo(target_, "cannot move the finished file into place", reason);
  }
}

void writeFilesAtomically(std::span<const OutputFile> files) {
  std::vector<std::unique_ptr<AtomicOutputFile>> temps;
  for (const OutputFile& file : files) {
    temps.push_back(std::make_unique<AtomicOutputFile>(file.path));
    std::ofstream stream(temps.back()->tempPath(), std::ios::binary | std::ios::trunc);
    stream.write(reinterpret_cast<const char*>(file.bytes.data()), std::streamsize(file.bytes.size()));
    stream.flush();
    if (!stream) throwIo(file.path, "write failed", "disk full or I/O error");
  }
  for (const auto& temp : temps) temp->commit();
}

}  // namespace ht::frame_io
