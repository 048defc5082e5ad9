// status_mapping.cpp - see status_mapping.h.
#include "server/status_mapping.h"

#include <array>
#include <new>

#include "scene/scene_limits.h"
#include "scene/scene_source.h"

namespace ht::server {
namespace {

using grpc::StatusCode;

template <class E>
bool is(const Error& error) {
  return dynamic_cast<const E*>(&error) != nullptr;
}

struct StatusRule {
  bool (*matches)(const Error&);
  StatusCode code;
};

// First match wins: a derived type comes before its base (DiskFull and OutputConflict are IoErrors,
// SceneOutsideRoot and SceneLimitExceeded SceneErrors).
constexpr std::array kRules = {
    StatusRule{is<AccessDenied>, StatusCode::PERMISSION_DENIED},
    StatusRule{is<BadRequest>, StatusCode::INVALID_ARGUMENT},
    StatusRule{is<LimitExceeded>, StatusCode::RESOURCE_EXHAUSTED},
    StatusRule{is<DiskFull>, StatusCode::RESOURCE_EXHAUSTED},
    StatusRule{is<NameTaken>, StatusCode::ALREADY_EXISTS},
    StatusRule{is<OutputConflict>, StatusCode::FAILED_PRECONDITION},
    StatusRule{is<NoPanelSink>, StatusCode::FAILED_PRECONDITION},
    StatusRule{is<UnknownDisplay>, StatusCode::NOT_FOUND},
    StatusRule{is<UnknownScene>, StatusCode::NOT_FOUND},
    StatusRule{is<ShuttingDown>, StatusCode::UNAVAILABLE},
    StatusRule{is<ClientGone>, StatusCode::CANCELLED},
    StatusRule{is<SceneOutsideRoot>, StatusCode::PERMISSION_DENIED},
    StatusRule{is<SceneLimitExceeded>, StatusCode::RESOURCE_EXHAUSTED},
    StatusRule{is<ConfigError>, StatusCode::INVALID_ARGUMENT},
    StatusRule{is<SceneError>, StatusCode::INVALID_ARGUMENT},
    StatusRule{is<UsageError>, StatusCode::INVALID_ARGUMENT},
    StatusRule{is<GpuError>, StatusCode::INTERNAL},
    StatusRule{is<IoError>, StatusCode::INTERNAL},
};

}  // namespace

StatusCode statusCodeOf(const Error& error) {
  for (const StatusRule& rule : kRules) {
    if (rule.matches(error)) return rule.code;
  }
  return StatusCode::INTERNAL;
}

grpc::Status statusFromException(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const GpuError& e) {
    return grpc::Status(statusCodeOf(e), std::string("GPU: ") + e.what());
  } catch (const Error& e) { return grpc::Status(statusCodeOf(e), e.what()); } catch (const std::bad_alloc&) {
    return grpc::Status(StatusCode::RESOURCE_EXHAUSTED, "out of memory");
  } catch (const std::exception& e) { return grpc::Status(StatusCode::INTERNAL, e.what()); } catch (...) {
    return grpc::Status(StatusCode::INTERNAL, "unknown error");
  }
}

grpc::Status guarded(const std::function<grpc::Status()>& body) {
  try {
    return body();
  } catch (...) { return statusFromException(std::current_exception()); }
}

}  // namespace ht::server
