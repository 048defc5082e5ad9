// screen_check.cpp - see screen_check.h.
#include "tests/present/screen_check.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "frame_io/image_reading.h"
#include "frame_io/pixel_encoding.h"
#include "present/screen_capture.h"

namespace ht::present::test {

std::vector<std::uint8_t> pngRgb(const std::filesystem::path& png) {
  const frame_io::ImageFile image = frame_io::readImageFile(png);
  std::vector<std::uint8_t> rgb;
  rgb.reserve(image.rgba.size() / 4 * 3);
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) rgb.push_back(frame_io::srgbEncode8(image.rgba[i + c]));
  }
  return rgb;
}

namespace {

std::size_t differingBytes(const std::vector<std::uint8_t>& screen, const std::vector<std::uint8_t>& expected) {
  if (screen.size() != expected.size()) return expected.size();
  std::size_t bad = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) bad += screen[i] != expected[i];
  return bad;
}

}  // namespace

std::size_t screenMismatches(const XConnection& x, const Rect& rect, const std::vector<std::uint8_t>& expected,
                             std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::size_t bad = differingBytes(captureRgb(x, rect), expected);
  while (bad != 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    bad = differingBytes(captureRgb(x, rect), expected);
  }
  return bad;
}

pid_t startProcess(const std::string& exe, const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::vector<std::string> argv = {exe};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (std::string& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  const std::string logPath = log.string();
  const pid_t pid = fork();
  if (pid == 0) {
    FILE* f = std::fopen(logPath.c_str(), "w");
    if (f) {
      dup2(fileno(f), STDOUT_FILENO);
      dup2(fileno(f), STDERR_FILENO);
    }
    execv(cargs[0], cargs.data());
    _exit(127);
  }
  return pid;
}

int waitExit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace ht::present::test
