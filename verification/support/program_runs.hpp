// Running the `epicycle` program from a test (to kill it midway) and reading what it wrote.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace epicycle::test {

/// Starts args[0] with `args`, its standard output to /dev/null; the child's pid (wait for it or
/// kill it).
inline pid_t SpawnQuiet(const std::vector<std::string>& args) {
  std::fflush(nullptr);  // the child must not write the parent's buffered output again
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    if (std::freopen("/dev/null", "w", stdout) == nullptr) _exit(126);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

/// The bytes of a file ("" if it cannot be read).
/// Runs args[0] with `args` (standard output to /dev/null) to its end; its exit status, or −1 if
/// it did not exit normally.
inline int ExitStatus(const std::vector<std::string>& args) {
  const pid_t pid = SpawnQuiet(args);
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

inline std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A fresh folder under the system's temporary directory, removed at the end of the test.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag) {
    path = std::filesystem::temp_directory_path() /
           ("epicycle-" + tag + "-" + std::to_string(::getpid()) + "-" +
            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code e;
    std::filesystem::remove_all(path, e);
  }
  std::string File(const std::string& name) const { return (path / name).string(); }
};

}  // namespace epicycle::test
