// status_mapping.h - our error types -> gRPC status codes (docs/SERVICE.md "Errors"), one table keyed on the types
// (status_mapping.cpp). Handlers run their body through guarded(), so no exception ever escapes into gRPC and every
// failure carries a precise code.
#pragma once
#include <grpcpp/support/status.h>

#include <exception>
#include <functional>

#include "common/error.h"
#include "server/errors.h"

namespace ht::server {

// The code of an error by its type (the most derived type listed wins: DiskFull before IoError); INTERNAL for an
// ht::Error of no listed type.
grpc::StatusCode statusCodeOf(const Error& error);

// ht::Error -> its code with its message (GpuError prefixed "GPU: "); std::bad_alloc -> RESOURCE_EXHAUSTED; anything
// else -> INTERNAL.
grpc::Status statusFromException(std::exception_ptr error);

// Runs `body`; returns its status, or the mapped status of what it threw.
grpc::Status guarded(const std::function<grpc::Status()>& body);

}  // namespace ht::server
