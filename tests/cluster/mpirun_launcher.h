// mpirun_launcher.h - how the cluster tests start `mpirun` on this machine (docs/CLUSTER.md §6): oversubscribed, no
// core binding, shared memory and loopback only, CMA off, a hard time limit, as root, and a Mesa shader cache shared
// by the runs of one test program so lavapipe compiles the kernels once, not in every rank.
#pragma once
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "tests/cli/process_runner.h"

namespace ht::test {

// Launcher flags: oversubscribe the 2 cores, no core binding (a bound rank would share one core with lavapipe's
// threads), shared memory and loopback only, CMA off (containers without ptrace rights), a hard time limit.
inline const std::vector<std::string> kLauncherFlags = {"--oversubscribe",
                                                        "--bind-to",
                                                        "none",
                                                        "--mca",
                                                        "btl",
                                                        "self,vader",
                                                        "--mca",
                                                        "btl_tcp_if_include",
                                                        "lo",
                                                        "--mca",
                                                        "oob_tcp_if_include",
                                                        "lo",
                                                        "--mca",
                                                        "btl_vader_single_copy_mechanism",
                                                        "none",
                                                        "--timeout",
                                                        "120"};

// The environment of the launched jobs; returns the shader cache directory to remove at the end.
inline std::filesystem::path prepareMpirunEnvironment() {
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);  // tests run as root in CI
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
#ifdef HT_SANITIZED_BUILD
  // The ASan suite: the ranks keep ASan and UBSan but not the leak check, because Open MPI's components
  // (dlopen'ed plugins without frame pointers) leave small allocations whose stacks LeakSanitizer cannot attribute
  // to a module that tests/lsan.supp could name. holotrace's own leaks are checked by its single-process tests.
  const char* asan = std::getenv("ASAN_OPTIONS");
  const std::string options = std::string(asan ? asan : "") + (asan && *asan ? ":" : "") + "detect_leaks=0";
  setenv("ASAN_OPTIONS", options.c_str(), 1);
#endif
  const std::filesystem::path cache =
      std::filesystem::temp_directory_path() / ("holotrace-mpirun-shaders-" + std::to_string(getpid()));
  unsetenv("MESA_SHADER_CACHE_DISABLE");
  setenv("MESA_SHADER_CACHE_DIR", cache.c_str(), 1);
  return cache;
}

// mpirun under a watchdog: Open MPI 4.1's mpirun was seen to stay up after every rank of a job with a killed rank
// had exited (its --timeout did not fire), which would hang the suite; `timeout` kills it after 150 s.
inline cli::test::ProcessResult launchMpirun(const std::vector<std::string>& mpirunArgs) {
  std::vector<std::string> all = {"-s", "KILL", "150", MPIEXEC_EXE};
  all.insert(all.end(), mpirunArgs.begin(), mpirunArgs.end());
  return cli::test::runProcess("/usr/bin/timeout", all);
}

}  // namespace ht::test
