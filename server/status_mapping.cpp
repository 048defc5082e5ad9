// status_mapping.cpp - see status_mapping.h.
#include "server/status_mapping.h"

#include <new>

#include "common/error.h"
#include "server/display_registry.h"
#include "server/file_sink.h"
#include "server/path_rules.h"
#include "server/render_worker.h"
#include "server/scene_library.h"

namespace ht::server {

grpc::Status statusFromException(std::exception_ptr error) {
  using grpc::Status;
  using grpc::StatusCode;
  try {
    std::rethrow_exception(error);
  } catch (const AccessDenied& e) {
    return Status(StatusCode::PERMISSION_DENIED, e.what());
  } catch (const BadRequest& e) {
    return Status(StatusCode::INVALID_ARGUMENT, e.what());
  } catch (const LimitExceeded& e) {
    return Status(StatusCode::RESOURCE_EXHAUSTED, e.what());
  } catch (const DiskFull& e) {
    return Status(StatusCode::RESOURCE_EXHAUSTED, e.what());
  } catch (const UnknownDisplay& e) {
    return Status(StatusCode::NOT_FOUND, e.what());
  } catch (const UnknownScene& e) {
    return Status(StatusCode::NOT_FOUND, e.what());
  } catch (const ShuttingDown& e) {
    return Status(StatusCode::UNAVAILABLE, e.what());
  } catch (const ClientGone& e) {
    return Status(StatusCode::CANCELLED, e.what());
  } catch (const ConfigError& e) {
    return Status(StatusCode::INVALID_ARGUMENT, e.what());
  } catch (const SceneError& e) {
    return Status(StatusCode::INVALID_ARGUMENT, e.what());
  } catch (const GpuError& e) {
    return Status(StatusCode::INTERNAL, std::string("GPU: ") + e.what());
  } catch (const IoError& e) {
    return Status(StatusCode::INTERNAL, e.what());
  } catch (const std::bad_alloc&) {
    return Status(StatusCode::RESOURCE_EXHAUSTED, "out of memory");
  } catch (const std::exception& e) {
    return Status(StatusCode::INTERNAL, e.what());
  } catch (...) {
    return Status(StatusCode::INTERNAL, "unknown error");
  }
}

grpc::Status guarded(const std::function<grpc::Status()>& body) {
  try {
    return body();
  } catch (...) {
    return statusFromException(std::current_exception());
  }
}

}  // namespace ht::server
