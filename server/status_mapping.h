// status_mapping.h - our error types -> gRPC status codes (docs/SERVICE.md "Errors"). Handlers run their body
// through guarded(), so no exception ever escapes into gRPC and every failure carries a precise code.
#pragma once
#include <grpcpp/support/status.h>

#include <exception>
#include <functional>
#include <stdexcept>

namespace ht::server {

// The client went away or cancelled the call.
class ClientGone : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

grpc::Status statusFromException(std::exception_ptr error);

// Runs `body`; returns its status, or the mapped status of what it threw.
grpc::Status guarded(const std::function<grpc::Status()>& body);

}  // namespace ht::server
