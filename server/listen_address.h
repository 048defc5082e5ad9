// listen_address.h - holotraced listens on unix sockets (a directory it creates 0750, the socket chmod 0660;
// not unix-abstract, which has no permissions, grpc/grpc doc/naming.md) or TCP on loopback only, and owns each
// address exclusively while it runs (docs/SERVICE.md §5 "One daemon per address").
#pragma once
#include <string>

#include "common/error.h"

namespace ht::server {

// Another process (another holotraced) serves or holds the address.
class AddressInUse : public IoError {
 public:
  using IoError::IoError;
};

// "unix:/abs/path" or a loopback TCP address whose host parses as an IPv4 address in 127.0.0.0/8 or as [::1], with
// a port 1..65535. Host names are refused (a name is not a loopback address, whatever it starts with).
void checkListenAddress(const std::string& configFile, const std::string& address);  // throws ConfigError

// One listen address owned by this daemon for its lifetime.
// Unix socket PATH: an exclusive flock(2) on PATH.lock (released by the kernel when the holder dies, so a crashed
// daemon leaves no stale lock; the file keeps the holder's pid for the message), then a liveness probe: connect()
// to an existing PATH: accepted = a server that takes no lock lives there (refused); refused = stale socket,
// removed. Only the holder removes the socket. TCP: a probe bind (SO_REUSEADDR, no SO_REUSEPORT) fails while
// anyone listens on the port; the gRPC server binds without SO_REUSEPORT too (daemon.cpp), so no two processes
// share a port.
class ListenClaim {
 public:
  explicit ListenClaim(std::string address);  // throws AddressInUse, IoError
  ~ListenClaim();                             // removes the socket (unix), releases the lock
  ListenClaim(ListenClaim&& other) noexcept;
  ListenClaim& operator=(ListenClaim&&) = delete;
  ListenClaim(const ListenClaim&) = delete;
  ListenClaim& operator=(const ListenClaim&) = delete;

  const std::string& address() const { return address_; }
  void finish() const;  // after binding: unix socket chmod 0660

 private:
  std::string address_;
  std::string socketPath_;  // empty for TCP
  int lockFd_ = -1;
};

}  // namespace ht::server
