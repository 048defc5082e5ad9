// listen_address.cpp - see listen_address.h.
#include "server/listen_address.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>

namespace ht::server {
namespace {

std::string unixPath(const std::string& address) {
  if (address.rfind("unix://", 0) == 0) return address.substr(7);
  if (address.rfind("unix:", 0) == 0) return address.substr(5);
  return {};
}

// A numeric loopback TCP address, parsed.
struct TcpAddress {
  sockaddr_storage storage{};
  socklen_t length = 0;
};

std::optional<std::uint16_t> parsePort(const std::string& text) {
  if (text.empty() || text.size() > 5) return std::nullopt;
  unsigned value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + static_cast<unsigned>(c - '0');
  }
  if (value == 0 || value > 65535) return std::nullopt;
  return static_cast<std::uint16_t>(value);
}

std::optional<TcpAddress> parseLoopback(const std::string& address) {
  TcpAddress out;
  if (address.rfind('[', 0) == 0) {  // [IPv6]:PORT
    const auto close = address.find("]:");
    if (close == std::string::npos) return std::nullopt;
    const auto port = parsePort(address.substr(close + 2));
    auto* in6 = reinterpret_cast<sockaddr_in6*>(&out.storage);
    if (!port || ::inet_pton(AF_INET6, address.substr(1, close - 1).c_str(), &in6->sin6_addr) != 1) return std::nullopt;
    if (!IN6_IS_ADDR_LOOPBACK(&in6->sin6_addr)) return std::nullopt;
    in6->sin6_family = AF_INET6;
    in6->sin6_port = htons(*port);
    out.length = sizeof(sockaddr_in6);
    return out;
  }
  const auto colon = address.rfind(':');
  if (colon == std::string::npos) return std::nullopt;
  const auto port = parsePort(address.substr(colon + 1));
  auto* in4 = reinterpret_cast<sockaddr_in*>(&out.storage);
  if (!port || ::inet_pton(AF_INET, address.substr(0, colon).c_str(), &in4->sin_addr) != 1) return std::nullopt;
  if ((ntohl(in4->sin_addr.s_addr) >> 24) != 127) return std::nullopt;
  in4->sin_family = AF_INET;
  in4->sin_port = htons(*port);
  out.length = sizeof(sockaddr_in);
  return out;
}

std::string errnoText(int err) { return std::strerror(err); }

// The pid a holder wrote into the lock file ("" if none).
std::string lockHolder(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid = n > 0 ? std::string(text, static_cast<std::size_t>(n)) : std::string();
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid;
}

int lockSocketPath(const std::string& address, const std::string& path) {
  const std::string lockPath = path + ".lock";
  const int fd = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (fd < 0) throw IoError("cannot open lock file " + lockPath + ": " + errnoText(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    const std::string holder = lockHolder(fd);
    ::close(fd);
    if (err == EWOULDBLOCK) {
      throw AddressInUse(address + " is owned by another holotraced" +
                         (holder.empty() ? std::string() : " (pid " + holder + ")") + ", lock file " + lockPath +
                         "; stop it first or give this daemon another listen address");
    }
    throw IoError("cannot lock " + lockPath + ": " + errnoText(err));
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    // The pid is only for the message; the lock holds without it.
  }
  return fd;
}

// True if a server accepts connections on the unix socket `path`.
bool socketIsLive(const std::string& path) {
  sockaddr_un addr{};
  if (path.size() >= sizeof addr.sun_path) return false;
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  const bool live = ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
  ::close(fd);
  return live;
}

void removeStaleSocket(const std::string& address, const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return;
  if (!S_ISSOCK(st.st_mode)) {
    throw AddressInUse(address + ": " + path +
                       " exists and is not a socket; remove it or choose "
                       "another listen address");
  }
  if (socketIsLive(path)) {
    throw AddressInUse(address +
                       " is served by another process that holds no lock (an older "
                       "holotraced?); stop it first or give this daemon another listen address");
  }
  ::unlink(path.c_str());
}

void probeTcpPort(const std::string& address) {
  const std::optional<TcpAddress> tcp = parseLoopback(address);
  if (!tcp) return;  // checkListenAddress refuses it first
  const int fd = ::socket(tcp->storage.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw IoError("socket(): " + errnoText(errno));
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);  // TIME_WAIT of an earlier run is no owner
  const int rc = ::bind(fd, reinterpret_cast<const sockaddr*>(&tcp->storage), tcp->length);
  const int err = errno;
  ::close(fd);
  if (rc == 0) return;
  if (err == EADDRINUSE) {
    throw AddressInUse(address +
                       " is in use by another process (another holotraced?); stop it "
                       "first or give this daemon another port");
  }
  throw IoError("cannot bind " + address + ": " + errnoText(err));
}

}  // namespace

void checkListenAddress(const std::string& configFile, const std::string& address) {
  const std::string path = unixPath(address);
  if (!path.empty()) {
    if (path.front() != '/') throw ConfigError(configFile, "listen", address, "unix:/absolute/path");
    return;
  }
  if (!parseLoopback(address)) {
    throw ConfigError(configFile, "listen", address,
                      "unix:/path or a numeric loopback TCP address with a port 1-65535 (127.0.0.1:PORT, [::1]:PORT)");
  }
}

ListenClaim::ListenClaim(std::string address) : address_(std::move(address)), socketPath_(unixPath(address_)) {
  if (socketPath_.empty()) {
    probeTcpPort(address_);
    return;
  }
  const std::filesystem::path dir = std::filesystem::path(socketPath_).parent_path();
  std::error_code ec;
  if (std::filesystem::create_directories(dir, ec)) ::chmod(dir.c_str(), 0750);
  lockFd_ = lockSocketPath(address_, socketPath_);
  try {
    removeStaleSocket(address_, socketPath_);
  } catch (...) {
    ::close(lockFd_);
    throw;
  }
}

ListenClaim::ListenClaim(ListenClaim&& other) noexcept
    : address_(std::move(other.address_)), socketPath_(std::move(other.socketPath_)), lockFd_(other.lockFd_) {
  other.socketPath_.clear();
  other.lockFd_ = -1;
}

ListenClaim::~ListenClaim() {
  if (lockFd_ < 0) return;
  ::unlink(socketPath_.c_str());  // ours: we hold the lock
  ::close(lockFd_);
}

void ListenClaim::finish() const {
  if (!socketPath_.empty()) ::chmod(socketPath_.c_str(), 0660);
}

}  // namespace ht::server
