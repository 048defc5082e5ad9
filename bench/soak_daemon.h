// soak_daemon.h - a holotraced child for the soak program: a private temp directory (scene root with OBJ scenes,
// output root, socket, config with short idle/stall limits so that every release path runs during the soak), started
// with posix_spawn (its log goes to a file there), stopped with SIGTERM.
#pragma once
#include <sys/types.h>

#include <filesystem>
#include <string>

namespace ht::bench {

// The limits the spawned daemon runs with (docs/SERVICE.md §10).
inline constexpr double kSoakSceneIdleSeconds = 3.0;

class SoakDaemon {
 public:
  SoakDaemon(const std::string& exe, const std::string& displaysDir);  // throws std::runtime_error
  ~SoakDaemon();                                                       // SIGKILL if still running; removes the dir
  SoakDaemon(const SoakDaemon&) = delete;
  SoakDaemon& operator=(const SoakDaemon&) = delete;

  std::string address() const { return "unix:" + (dir_ / "run" / "soak.sock").string(); }
  std::filesystem::path outputRoot() const { return dir_ / "out"; }
  std::filesystem::path logFile() const { return dir_ / "holotraced.log"; }
  pid_t pid() const { return pid_; }
  int stop();  // SIGTERM, waits up to 30 s; the exit status (-1 = did not exit)

 private:
  std::filesystem::path dir_;
  pid_t pid_ = -1;
  bool exited_ = false;
};

// The OBJ text of a grid of 2 * n * n triangles at height z (distinct z: distinct content).
std::string soakGridObj(int n, int z);

}  // namespace ht::bench
