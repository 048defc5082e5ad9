// errors.h - the daemon's error types. Each derives from ht::Error (common/error.h) like every other failure of
// holotrace, carries a message that names the field or value at fault, and maps to one gRPC status code
// (server/status_mapping.h, docs/SERVICE.md "Errors"). Code catches by type, never by parsing text.
#pragma once
#include <string>

#include "common/error.h"

namespace ht::server {

// A client asked for something outside the daemon's roots: `..`, an absolute path, a symlink leading out
// (-> PERMISSION_DENIED).
class AccessDenied : public Error {
 public:
  using Error::Error;
};

// A request field is malformed; `field` names it (-> INVALID_ARGUMENT). what(): "<field>: <problem>".
class BadRequest : public Error {
 public:
  BadRequest(std::string field, const std::string& problem) : Error(field + ": " + problem), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// A request exceeds a configured limit (-> RESOURCE_EXHAUSTED).
class LimitExceeded : public Error {
 public:
  using Error::Error;
};

// The disk or quota is full, or a file exceeds the file-size limit (EFBIG: RLIMIT_FSIZE, filesystem maximum): the
// file was not written, nothing partial remains (-> RESOURCE_EXHAUSTED). An IoError the client can act on.
class DiskFull : public IoError {
 public:
  using IoError::IoError;
};

// A capture name already has files under the output root, or another capture is writing it (-> ALREADY_EXISTS).
class NameTaken : public Error {
 public:
  using Error::Error;
};

// Something that is not a file of ours sits where an output file must go, e.g. a directory (-> FAILED_PRECONDITION):
// the message names it; the operator must move it.
class OutputConflict : public IoError {
 public:
  using IoError::IoError;
};

// An unknown display id (-> NOT_FOUND).
class UnknownDisplay : public Error {
 public:
  using Error::Error;
};

// A request asks to show frames on a display that has no panel sink (not in the config's "present", or removed
// by SIGHUP) (-> FAILED_PRECONDITION): the message names the display and the config field to change.
class NoPanelSink : public Error {
 public:
  using Error::Error;
};

// The handle names no loaded scene (-> NOT_FOUND).
class UnknownScene : public Error {
 public:
  using Error::Error;
};

// The daemon is stopping: the job never ran (-> UNAVAILABLE).
class ShuttingDown : public Error {
 public:
  using Error::Error;
};

// The client went away or cancelled the call (-> CANCELLED).
class ClientGone : public Error {
 public:
  using Error::Error;
};

}  // namespace ht::server
