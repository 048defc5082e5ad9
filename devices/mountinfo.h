// mountinfo.h - parses /proc/<pid>/mountinfo (proc(5)): each mount's mount point, source and file system type.
// Paths in the file escape space, tab, newline and backslash as octal (\040, \011, \012, \134); they are decoded.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace ht::devices {

struct MountEntry {
  std::filesystem::path mountPoint;
  std::string source;  // e.g. "/dev/sdb1"
  std::string fsType;  // e.g. "vfat"
};

// Malformed lines are skipped (the kernel writes the file; a line we cannot read is not a mount we can use).
std::vector<MountEntry> parseMountinfo(std::string_view text);

// Decodes the octal escapes of one mountinfo field ("a\040b" -> "a b"); other backslashes stay as they are.
std::string decodeMountinfoField(std::string_view field);

}  // namespace ht::devices
