// error.h - the error types of holotrace. Every user-facing failure is one of these types; the message
// names the file / field / value at fault and how to fix it. Callers catch by type, never by parsing text.
#pragma once
#include <stdexcept>
#include <string>

namespace ht {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A display config / visual.json problem. what(): "<file>: field '<field>' = <value>: <expected>".
class ConfigError : public Error {
 public:
  ConfigError(std::string file, std::string field, std::string value, std::string expected)
      : Error(file + ": field '" + field + "' = " + value + ": " + expected),
        file_(std::move(file)),
        field_(std::move(field)),
        value_(std::move(value)),
        expected_(std::move(expected)) {}
  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& value() const { return value_; }
  const std::string& expected() const { return expected_; }

 private:
  std::string file_, field_, value_, expected_;
};

// A scene file (glTF/GLB/OBJ) that cannot be loaded. what(): "<file>: <what is wrong> (<how to fix>)".
class SceneError : public Error {
 public:
  SceneError(std::string file, const std::string& problem) : Error(file + ": " + problem), file_(std::move(file)) {}
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

// Vulkan / device failure, or a GPU-side error flag the host read back (e.g. traversal step limit).
class GpuError : public Error {
 public:
  using Error::Error;
};

// Reading or writing an output/input file failed (never leaves a partial file behind).
class IoError : public Error {
 public:
  using Error::Error;
};

// Command-line usage error (unknown flag, missing value): the CLI prints it with a pointer to --help.
class UsageError : public Error {
 public:
  using Error::Error;
};

}  // namespace ht
