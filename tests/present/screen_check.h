// screen_check.h - what the Xvfb tests of the display sink share: the RGB bytes a PNG shows on an 8-bit panel, the
// count of screen bytes that differ from them (polled until they match or a deadline passes), and `holotrace` started
// in the background with its output in a log file, ended by PID.
#pragma once
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "present/randr_snapshot.h"
#include "present/x_connection.h"

namespace ht::present::test {

// The PNG's pixels as R, G, B bytes, row 0 = top (8-bit sRGB, as the panel gets them).
std::vector<std::uint8_t> pngRgb(const std::filesystem::path& png);

// Bytes of `rect` on the X screen that differ from `expected`, re-read every 20 ms until none do or `timeout` passed.
std::size_t screenMismatches(const XConnection& x, const Rect& rect, const std::vector<std::uint8_t>& expected,
                             std::chrono::milliseconds timeout);

// Starts `exe args...` with stdout and stderr into `log`; returns its PID (end it with kill + waitExit).
pid_t startProcess(const std::string& exe, const std::vector<std::string>& args, const std::filesystem::path& log);

// Waits for `pid`; its exit status, or 128 + signal.
int waitExit(pid_t pid);

std::string readText(const std::filesystem::path& path);

}  // namespace ht::present::test
