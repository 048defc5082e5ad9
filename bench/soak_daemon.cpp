// soak_daemon.cpp - see soak_daemon.h.
#include "bench/soak_daemon.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

extern char** environ;

namespace ht::bench {

std::string soakGridObj(int n, int z) {
  std::ostringstream obj;
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) obj << "v " << x * 0.1 << " " << y * 0.1 << " " << z * 0.01 << "\n";
  }
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1, b = a + 1, c = a + n + 1, d = c + 1;
      obj << "f " << a << " " << b << " " << d << "\nf " << a << " " << d << " " << c << "\n";
    }
  }
  return obj.str();
}

namespace {

void writeFile(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string configJson(const std::filesystem::path& dir, const std::string& displaysDir) {
  const std::filesystem::path displays = std::filesystem::absolute(displaysDir);
  std::ostringstream c;
  c << R"({"displays_dir": ")" << displays.string() << R"(", "scene_root": "scenes", "output_root": "out",)"
    << R"( "work_dir": "work", "listen": ["unix:)" << (dir / "run" / "soak.sock").string() << R"("],)"
    << R"( "limits": {"max_clients": 24, "max_scene_sessions": 48, "scene_idle_seconds": )" << kSoakSceneIdleSeconds
    << R"(, "max_scene_memory_bytes": 16777216, "max_scene_bytes": 8388608, "max_upload_bytes_in_flight": 16777216,)"
    << R"( "max_uploads": 4, "upload_idle_seconds": 1.5, "stream_stall_seconds": 1.5}})";
  return c.str();
}

}  // namespace

SoakDaemon::SoakDaemon(const std::string& exe, const std::string& displaysDir) {
  dir_ = std::filesystem::temp_directory_path() / ("holotrace-soak-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir_);
  for (int z = 0; z < 6; ++z) writeFile(dir_ / "scenes" / ("grid" + std::to_string(z) + ".obj"), soakGridObj(60, z));
  std::filesystem::create_directories(dir_ / "out");
  writeFile(dir_ / "holotraced.json", configJson(dir_, displaysDir));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, logFile().c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const std::string config = (dir_ / "holotraced.json").string();
  std::vector<char*> argv = {const_cast<char*>(exe.c_str()), const_cast<char*>("--config"),
                             const_cast<char*>(config.c_str()), nullptr};
  const int rc = ::posix_spawn(&pid_, exe.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + exe);
}

int SoakDaemon::stop() {
  if (exited_) return -1;
  ::kill(pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      exited_ = true;
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return -1;
}

SoakDaemon::~SoakDaemon() {
  if (pid_ > 0 && !exited_) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

}  // namespace ht::bench
