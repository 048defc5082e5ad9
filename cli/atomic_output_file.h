// atomic_output_file.h - write a file under a temporary name in the target's directory, then rename it
// into place, so a reader never sees a partial file. If commit() is never reached (an exception, an early
// return), the destructor removes the temporary file.
#pragma once
#include <filesystem>

namespace ht::cli {

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

}  // namespace ht::cli
