// atomic_output_file.h - write a file under a temporary name in the target's directory, then rename it
// into place, so a reader never sees a partial file. If commit() is never reached (an exception, an early
// return), the destructor removes the temporary file.
//
// writeFilesAtomically() commits a set of files (the views of one frame, a quilt and its metadata): every file is
// written under its temporary name before the first one is renamed into place, so a failure while writing leaves
// none of them.
#pragma once
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace ht::frame_io {

// Creates the directory `target` will be written to (and its parents) and checks that it is writable, so a
// command can fail before expensive work rather than after it. Throws IoError naming the path and reason.
void prepareOutputDirectory(const std::filesystem::path& target);

class AtomicOutputFile {
 public:
  // Creates the parent directory (and its parents) if needed and a fresh, empty temporary file next to
  // `target`. Throws IoError naming the path and the reason.
  explicit AtomicOutputFile(std::filesystem::path target);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  // Where the content must be written before commit().
  const std::filesystem::path& tempPath() const { return temp_; }
  const std::filesystem::path& targetPath() const { return target_; }

  // Renames the temporary file onto the target (atomic on POSIX). Throws IoError on failure; the temporary
  // file is removed either way.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// A complete file to write.
struct OutputFile {
  std::filesystem::path path;
  std::vector<std::uint8_t> bytes;
};

// Writes each file to its temporary name (creating parent directories), then renames them all into place in order.
// Throws IoError naming the path and the reason; if writing fails, no file of the set appears and files of the same
// names stay as they were. (A rename failing after earlier ones succeeded, which the writable directory makes
// unlikely, leaves the earlier files in place.)
void writeFilesAtomically(std::span<const OutputFile> files);

}  // namespace ht::frame_io
