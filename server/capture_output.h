// capture_output.h - where one Capture's files go (docs/SERVICE.md §7 "Capture names"): the name is the capture's
// own while it runs (a second capture of the same name is refused), files already under that name are refused
// unless the request says overwrite (then they are removed before the first new frame, so old and new frames never
// mix), and each frame's files appear as a set, whole or not at all (FileSink::writeFiles).
#pragma once
#include <span>
#include <string>

#include "frame_io/frame_package.h"
#include "server/file_sink.h"

namespace ht::server {

// True when `file` is one of the files a capture named `name` writes: NAME_fDIGITS followed by the extension,
// a quilt tag (_qs...) or a view index (_v...). "take_f0001_f0000.png" (capture "take_f0001") is not one of "take".
bool isCaptureFileOf(const std::string& name, const std::string& file);

class CaptureOutput {
 public:
  // Throws NameTaken (another capture runs under `name`, or files of it exist and !overwrite), OutputConflict (a
  // directory among them) or IoError.
  CaptureOutput(FileSink& sink, std::string name, bool overwrite);
  ~CaptureOutput();
  CaptureOutput(const CaptureOutput&) = delete;
  CaptureOutput& operator=(const CaptureOutput&) = delete;

  void writeFrame(std::span<const frame_io::FrameFile> files) { sink_.writeFiles(files); }

 private:
  FileSink& sink_;
  std::string name_;
};

}  // namespace ht::server
