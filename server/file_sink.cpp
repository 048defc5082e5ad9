// file_sink.cpp - see file_sink.h.
#include "server/file_sink.h"

#include <dirent.h>
#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <vector>

#include "common/error.h"

namespace ht::server {
namespace {

std::string errnoText(int err) { return std::strerror(err); }

[[noreturn]] void throwWriteError(const std::string& name, int err) {
  if (err == ENOSPC || err == EDQUOT) throw DiskFull("output disk full while writing " + name + ": " + errnoText(err));
  if (err == EFBIG) throw DiskFull("file size limit reached while writing " + name + ": " + errnoText(err));
  if (err == EISDIR || err == ENOTEMPTY || err == EEXIST || err == ENOTDIR)
    throw OutputConflict("cannot write " + name + ": a directory of that name is in the way (" + errnoText(err) +
                         "); move it or choose another name");
  throw IoError("cannot write " + name + ": " + errnoText(err));
}

std::string tempNameFor(const std::string& name) {
  static std::atomic<std::uint64_t> counter{0};
  return "." + name + ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
}

}  // namespace

FileSink::FileSink(const std::filesystem::path& root, FileOps ops) : ops_(std::move(ops)) {
  std::error_code ec;
  std::filesystem::create_directories(root, ec);
  rootFd_ = ::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (rootFd_ < 0) throw IoError("cannot open output root " + root.string() + ": " + errnoText(errno));
}

FileSink::~FileSink() {
  if (rootFd_ >= 0) ::close(rootFd_);
}

int FileSink::openTemp(const std::string& tempName) {
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW;
  open_how how{};
  how.flags = static_cast<std::uint64_t>(flags);
  how.mode = 0640;
  how.resolve = RESOLVE_BENEATH | RESOLVE_NO_SYMLINKS;
  const long fd = ::syscall(SYS_openat2, rootFd_, tempName.c_str(), &how, sizeof how);
  if (fd >= 0 || errno != ENOSYS) return static_cast<int>(fd);
  return ::openat(rootFd_, tempName.c_str(), flags, 0640);  // kernel < 5.6; the name is one checked component
}

int FileSink::writeAll(int fd, std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ops_.write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    if (n == 0) return EIO;  // no progress and no error: do not spin
    done += static_cast<std::size_t>(n);
  }
  return 0;
}

int FileSink::writeTemp(const std::string& temp, std::span<const std::uint8_t> bytes) {
  const int fd = openTemp(temp);
  if (fd < 0) return errno;
  int err = writeAll(fd, bytes);
  if (err == 0 && ops_.fsync(fd) != 0) err = errno;  // NFS and quotas may report ENOSPC/EDQUOT only here
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) ::unlinkat(rootFd_, temp.c_str(), 0);
  return err;
}

void FileSink::writeFile(const std::string& name, std::span<const std::uint8_t> bytes) {
  const frame_io::FrameFile file{name, {bytes.begin(), bytes.end()}};
  writeFiles({&file, 1});
}

void FileSink::writeFiles(std::span<const frame_io::FrameFile> files) {
  std::vector<std::string> temps;
  const auto removeTemps = [&](std::size_t from) {
    for (std::size_t i = from; i < temps.size(); ++i) ::unlinkat(rootFd_, temps[i].c_str(), 0);
  };
  for (const frame_io::FrameFile& file : files) {
    const std::string temp = tempNameFor(file.name);
    if (const int err = writeTemp(temp, file.bytes); err != 0) {
      removeTemps(0);
      throwWriteError(file.name, err);
    }
    temps.push_back(temp);
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (::renameat(rootFd_, temps[i].c_str(), rootFd_, files[i].name.c_str()) != 0) {
      const int err = errno;
      removeTemps(i);
      for (std::size_t k = 0; k < i; ++k) ::unlinkat(rootFd_, files[k].name.c_str(), 0);
      throwWriteError(files[i].name, err);
    }
  }
}

std::vector<std::string> FileSink::list(const std::function<bool(const std::string&)>& keep) const {
  const int fd = ::openat(rootFd_, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);  // fdopendir owns (and closes) it
  DIR* dir = fd < 0 ? nullptr : ::fdopendir(fd);
  if (dir == nullptr) {
    const int err = errno;
    if (fd >= 0) ::close(fd);
    throw IoError("cannot list the output root: " + errnoText(err));
  }
  std::vector<std::string> names;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (!name.empty() && name.front() != '.' && keep(name)) names.push_back(name);
  }
  ::closedir(dir);
  return names;
}

void FileSink::remove(const std::string& name) {
  if (::unlinkat(rootFd_, name.c_str(), 0) == 0 || errno == ENOENT) return;
  const int err = errno;
  if (err == EISDIR || err == EPERM)
    throw OutputConflict("cannot replace " + name + ": it is a directory (move it or choose another name)");
  throw IoError("cannot remove " + name + ": " + errnoText(err));
}

bool FileSink::claim(const std::string& name) {
  std::lock_guard lock(claimsMutex_);
  return claims_.insert(name).second;
}

void FileSink::release(const std::string& name) {
  std::lock_guard lock(claimsMutex_);
  claims_.erase(name);
}

}  // namespace ht::server
