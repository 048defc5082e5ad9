// path_rules.h - client-supplied names and paths, checked before any file system call (docs/SERVICE.md §6
// "Output confinement"). Violations throw AccessDenied (-> PERMISSION_DENIED) or BadRequest (-> INVALID_ARGUMENT).
#pragma once
#include <filesystem>
#include <string>

#include "server/errors.h"

namespace ht::server {

// A name that may become one path component: [A-Za-z0-9._-], 1..100 chars, not "." or "..", no leading '.'.
void checkFileNameComponent(const std::string& field, const std::string& name);

// A relative path below `root` with no "..", no absolute form, no empty component; returns root / path.
std::filesystem::path resolveBeneath(const std::filesystem::path& root, const std::string& field,
                                     const std::string& relative);

}  // namespace ht::server
