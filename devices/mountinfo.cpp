// mountinfo.cpp - see mountinfo.h.
#include "devices/mountinfo.h"

#include <algorithm>
#include <optional>

namespace ht::devices {
namespace {

bool isOctal(char c) { return c >= '0' && c <= '7'; }

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t pos = 0;
  while (pos < line.size()) {
    const std::size_t start = line.find_first_not_of(' ', pos);
    if (start == std::string_view::npos) break;
    const std::size_t end = std::min(line.find(' ', start), line.size());
    fields.push_back(line.substr(start, end - start));
    pos = end;
  }
  return fields;
}

// Line layout: id parent major:minor root mount-point options [optional fields...] - fstype source super-options
std::optional<MountEntry> parseLine(std::string_view line) {
  const std::vector<std::string_view> fields = splitFields(line);
  if (fields.size() < 7) return std::nullopt;
  std::size_t separator = 6;
  while (separator < fields.size() && fields[separator] != "-") ++separator;
  if (separator + 2 >= fields.size()) return std::nullopt;
  return MountEntry{decodeMountinfoField(fields[4]), decodeMountinfoField(fields[separator + 2]),
                    decodeMountinfoField(fields[separator + 1])};
}

}  // namespace

std::string decodeMountinfoField(std::string_view field) {
  std::string out;
  out.reserve(field.size());
  for (std::size_t i = 0; i < field.size(); ++i) {
    if (field[i] == '\\' && i + 3 < field.size() && isOctal(field[i + 1]) && isOctal(field[i + 2]) &&
        isOctal(field[i + 3])) {
      const int value = (field[i + 1] - '0') * 64 + (field[i + 2] - '0') * 8 + (field[i + 3] - '0');
      if (value <= 0xff) {
        out.push_back(static_cast<char>(value));
        i += 3;
        continue;
      }
    }
    out.push_back(field[i]);
  }
  return out;
}

std::vector<MountEntry> parseMountinfo(std::string_view text) {
  std::vector<MountEntry> mounts;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    if (auto entry = parseLine(text.substr(pos, end - pos))) mounts.push_back(std::move(*entry));
    pos = end + 1;
  }
  return mounts;
}

}  // namespace ht::devices
