// path_rules.cpp - see path_rules.h.
#include "server/path_rules.h"

#include <algorithm>

namespace ht::server {

void checkFileNameComponent(const std::string& field, const std::string& name) {
  if (name.find('/') != std::string::npos || name == "..") {
    throw AccessDenied(field + " '" + name + "' is not a single path component");
  }
  if (name.empty() || name.size() > 100) throw BadRequest(field, "must have 1..100 characters");
  const bool allowed = std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
           c == '-';
  });
  if (!allowed || name.front() == '.') {
    throw BadRequest(field, "'" + name + "' may use only A-Z a-z 0-9 . _ - and must not start with '.'");
  }
}

std::filesystem::path resolveBeneath(const std::filesystem::path& root, const std::string& field,
                                     const std::string& relative) {
  if (relative.empty()) throw BadRequest(field, "is empty");
  if (relative.find('\0') != std::string::npos) throw BadRequest(field, "contains a NUL byte");
  const std::filesystem::path p(relative);
  if (p.is_absolute()) throw AccessDenied(field + " '" + relative + "' is absolute; give a path below the root");
  for (const auto& part : p) {
    if (part == "..") throw AccessDenied(field + " '" + relative + "' leaves the root ('..')");
  }
  return root / p.lexically_normal();
}

}  // namespace ht::server
