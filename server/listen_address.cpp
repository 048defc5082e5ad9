// listen_address.cpp - see listen_address.h.
#include "server/listen_address.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "common/error.h"

namespace ht::server {
namespace {

std::string unixPath(const std::string& address) {
  if (address.rfind("unix://", 0) == 0) return address.substr(7);
  if (address.rfind("unix:", 0) == 0) return address.substr(5);
  return {};
}

bool isLoopback(const std::string& address) {
  return address.rfind("127.", 0) == 0 || address.rfind("[::1]:", 0) == 0 || address.rfind("localhost:", 0) == 0;
}

}  // namespace

void checkListenAddress(const std::string& configFile, const std::string& address) {
  const std::string path = unixPath(address);
  if (!path.empty()) {
    if (path.front() != '/') throw ConfigError(configFile, "listen", address, "unix:/absolute/path");
    return;
  }
  if (!isLoopback(address)) {
    throw ConfigError(configFile, "listen", address,
                      "unix:/path or a loopback TCP address (127.0.0.1:PORT, [::1]:PORT)");
  }
}

void prepareListenAddress(const std::string& address) {
  const std::string path = unixPath(address);
  if (path.empty()) return;
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (std::filesystem::create_directories(dir, ec)) ::chmod(dir.c_str(), 0750);
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISSOCK(st.st_mode)) ::unlink(path.c_str());  // stale socket
}

void finishListenAddress(const std::string& address) {
  const std::string path = unixPath(address);
  if (!path.empty()) ::chmod(path.c_str(), 0660);
}

void removeListenAddress(const std::string& address) {
  const std::string path = unixPath(address);
  if (!path.empty()) ::unlink(path.c_str());
}

}  // namespace ht::server
