// capture_output.cpp - see capture_output.h.
#include "server/capture_output.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace ht::server {

bool isCaptureFileOf(const std::string& name, const std::string& file) {
  const std::string stem = name + "_f";
  if (file.rfind(stem, 0) != 0) return false;
  std::size_t pos = stem.size();
  const std::size_t digitsStart = pos;
  while (pos < file.size() && std::isdigit(static_cast<unsigned char>(file[pos]))) ++pos;
  if (pos == digitsStart) return false;
  const std::string rest = file.substr(pos);
  return rest.rfind(".", 0) == 0 || rest.rfind("_qs", 0) == 0 || rest.rfind("_v", 0) == 0;
}

CaptureOutput::CaptureOutput(FileSink& sink, std::string name, bool overwrite) : sink_(sink), name_(std::move(name)) {
  if (!sink_.claim(name_)) throw NameTaken("capture name '" + name_ + "' is in use by a running capture");
  try {
    std::vector<std::string> existing = sink_.list([&](const std::string& f) { return isCaptureFileOf(name_, f); });
    std::sort(existing.begin(), existing.end());
    if (!existing.empty() && !overwrite) {
      throw NameTaken("capture name '" + name_ + "' already has " + std::to_string(existing.size()) +
                      " files under the output root (first: " + existing.front() +
                      "); choose another name or set overwrite");
    }
    for (const std::string& file : existing) sink_.remove(file);
  } catch (...) {
    sink_.release(name_);
    throw;
  }
}

CaptureOutput::~CaptureOutput() { sink_.release(name_); }

}  // namespace ht::server
