// listen_address.h - holotraced listens on unix sockets (a directory it creates 0750, the socket chmod 0660;
// not unix-abstract, which has no permissions, grpc/grpc doc/naming.md) or TCP on loopback only.
#pragma once
#include <string>

namespace ht::server {

void checkListenAddress(const std::string& configFile, const std::string& address);  // throws ConfigError
void prepareListenAddress(const std::string& address);  // unix: creates the directory, removes a stale socket
void finishListenAddress(const std::string& address);   // unix: chmod 0660
void removeListenAddress(const std::string& address);   // unix: unlinks the socket

}  // namespace ht::server
