// scene_source.cpp - see scene_source.h.
#include "scene/scene_source.h"

#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

#include "scene/gltf_file.h"

namespace ht {
namespace {

namespace fs = std::filesystem;

struct Fd {
  int fd = -1;
  explicit Fd(int f) : fd(f) {}
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
};

// Kernels before 5.6 have no openat2: walk the components, refusing "..", absolute paths and every symlink.
int openEachComponent(int dirFd, const std::string& relative, int flags) {
  if (relative.empty() || relative.front() == '/') return errno = EXDEV, -1;
  std::vector<std::string> parts;
  for (const auto& part : fs::path(relative)) {
    if (part == "..") return errno = EXDEV, -1;
    if (!part.empty() && part != ".") parts.push_back(part.string());
  }
  if (parts.empty()) return ::openat(dirFd, ".", flags | O_NOFOLLOW);
  int current = dirFd;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const bool last = i + 1 == parts.size();
    const int next = ::openat(current, parts[i].c_str(),
                              last ? flags | O_NOFOLLOW : O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    const int err = errno;
    if (current != dirFd) ::close(current);
    if (next < 0) return errno = err, -1;
    current = next;
  }
  return current;
}

// O_NONBLOCK: a FIFO planted under a scene name must not hang the open (regular files ignore the flag).
int openBeneath(int dirFd, const std::string& relative, int extraFlags = 0) {
  const int flags = O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK | extraFlags;
  open_how how{};
  how.flags = static_cast<std::uint64_t>(flags);
  how.resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS;
  const long fd = ::syscall(SYS_openat2, dirFd, relative.c_str(), &how, sizeof how);
  if (fd >= 0 || errno != ENOSYS) return static_cast<int>(fd);
  return openEachComponent(dirFd, relative, flags);
}

// Why an open failed, as the error the caller throws (or the text it records for an external file).
std::string openProblem(int err, const std::string& what) {
  if (err == ENOENT || err == ENOTDIR) return what + " not found (check the path and the working directory)";
  if (err == EXDEV || err == ELOOP) return what + " leads outside its directory (\"..\", absolute or a symlink out)";
  return what + " cannot be opened: " + std::strerror(err);
}

[[noreturn]] void throwOpenError(const std::string& name, int err) {
  if (err == EXDEV || err == ELOOP) throw SceneOutsideRoot(name, openProblem(err, "the path"));
  throw SceneError(name, openProblem(err, "file"));
}

// Reads the open regular file `fd`, charging its size to `budget` (bytes still allowed for the whole scene).
std::string readCharged(int fd, const std::string& name, std::uint64_t maxBytes, std::uint64_t& budget) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw SceneError(name, std::string("cannot stat the file: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw SceneError(name, "not a regular file (pass a scene file, not a directory or device)");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > budget)
    throw SceneLimitExceeded(name, "the scene's files are more than " + std::to_string(maxBytes) +
                                       " bytes (limit on the bytes loaded; this file alone is " + std::to_string(size) +
                                       ")");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw SceneError(name, "read only " + std::to_string(done) + " of " + std::to_string(size) +
                                 " bytes (the file changed while loading, or a read error occurred)");
    done += static_cast<std::size_t>(n);
  }
  budget -= size;
  return bytes;
}

bool referencesExternals(const std::string& name) {
  std::string ext = fs::path(name).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb";
}

// Reads every external URI of a glTF beneath `folderFd`. A URI that cannot be read is recorded, not thrown: the
// loader reports it only if the file really needs it (tinygltf treats a missing image as a warning).
void readExternals(int folderFd, SceneSource& source, std::uint64_t maxBytes, std::uint64_t& budget) {
  for (const std::string& uri : gltfExternalUris(source.name, source.bytes)) {
    if (source.externals.count(uri) || source.externalProblems.count(uri)) continue;
    const Fd fd(openBeneath(folderFd, uri));
    if (fd.fd < 0) {
      source.externalProblems[uri] =
          openProblem(errno, "'" + uri + "'") + "; external files must sit in the folder of the glTF file";
      continue;
    }
    source.externals[uri] = readCharged(fd.fd, source.name + " (external '" + uri + "')", maxBytes, budget);
  }
}

SceneSource readOpened(int mainFd, int folderFd, const std::string& name, std::uint64_t maxBytes) {
  SceneSource source;
  source.name = name;
  std::uint64_t budget = maxBytes;
  source.bytes = readCharged(mainFd, name, maxBytes, budget);
  if (referencesExternals(name)) readExternals(folderFd, source, maxBytes, budget);
  return source;
}

}  // namespace

SceneSource readSceneSourceBeneath(const fs::path& root, const std::string& relative, std::uint64_t maxBytes) {
  const Fd rootFd(::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (rootFd.fd < 0)
    throw SceneError(relative, "the scene root cannot be opened: " + std::string(std::strerror(errno)));
  const Fd file(openBeneath(rootFd.fd, relative));
  if (file.fd < 0) throwOpenError(relative, errno);
  const std::string folder = fs::path(relative).parent_path().string();
  const Fd folderFd(openBeneath(rootFd.fd, folder.empty() ? "." : folder, O_DIRECTORY));
  if (folderFd.fd < 0) throwOpenError(relative, errno);
  return readOpened(file.fd, folderFd.fd, relative, maxBytes);
}

SceneSource readSceneSource(const std::string& path, std::uint64_t maxBytes) {
  const Fd file(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (file.fd < 0) throwOpenError(path, errno);
  const std::string folder = fs::path(path).parent_path().string();
  const Fd folderFd(::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (folderFd.fd < 0) throwOpenError(path, errno);
  return readOpened(file.fd, folderFd.fd, path, maxBytes);
}

}  // namespace ht
