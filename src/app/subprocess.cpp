#include "app/subprocess.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

extern char** environ;

namespace gs {

std::string python_interpreter() {
  if (const char* p = std::getenv("GS_PYTHON"); p && *p) return p;
  std::error_code ec;
  return std::filesystem::exists("/usr/bin/python3", ec) ? "/usr/bin/python3" : "python3";
}

std::string run_process(const std::vector<std::string>& args) {
  if (args.empty()) return "nothing to run";
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
  if (rc != 0) return args[0] + " cannot be started (" + std::strerror(rc) + ")";
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return args[0] + " was not found";
  if (WIFSIGNALED(status))
    return args[0] + " was stopped by signal " + std::to_string(WTERMSIG(status));
  return args[0] + " exited with " + std::to_string(WEXITSTATUS(status));
}

}  // namespace gs
