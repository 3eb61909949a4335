#include "app/subprocess.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "app/locations.hpp"

extern char** environ;

namespace gs {
namespace {

// the first executable `name` on PATH, or ""
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir = ".";
    const std::string p = dir + "/" + name;
    struct stat st {};
    if (::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0)
      return p;
  }
  return "";
}

// start argv as `setup` says: {pid, 0}, or {-1, errno} when it cannot be started
std::pair<pid_t, int> spawn(const std::vector<std::string>& args, const ChildSetup& setup) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_copy;
  std::vector<char*> envp;
  if (setup.environment) {
    env_copy = *setup.environment;
    for (auto& e : env_copy) envp.push_back(e.data());
    envp.push_back(nullptr);
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (setup.stdin_null) posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  if (!setup.log.empty()) {
    posix_spawn_file_actions_addopen(&fa, 1, setup.log.c_str(),
                                     O_WRONLY | O_CREAT | (setup.append_log ? O_APPEND : O_TRUNC),
                                     0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
  }
  if (setup.quiet_stdout) posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  if (setup.quiet_stderr) posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, argv[0], &fa, nullptr, argv.data(),
                              setup.environment ? envp.data() : environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? std::pair<pid_t, int>{pid, 0} : std::pair<pid_t, int>{-1, rc};
}

// start argv and wait: {false, errno} when it cannot be started, else {true, waitpid status}
std::pair<bool, int> spawn_and_wait(const std::vector<std::string>& args, bool quiet_out,
                                    bool quiet_err,
                                    const std::vector<std::string>* environment = nullptr) {
  ChildSetup setup;
  setup.quiet_stdout = quiet_out;
  setup.quiet_stderr = quiet_err;
  setup.environment = environment;
  const auto [pid, err] = spawn(args, setup);
  if (pid < 0) return {false, err};
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return {true, status};
}

}  // namespace

pid_t start_process(const std::vector<std::string>& args, const ChildSetup& setup) {
  if (args.empty()) throw std::runtime_error("nothing to start");
  const auto [pid, err] = spawn(args, setup);
  if (pid < 0) throw std::runtime_error("cannot start " + args[0] + ": " + std::strerror(err));
  return pid;
}

bool python_has_charts(const std::string& python) {
  const auto [started, status] =
      spawn_and_wait({python, "-c", "import numpy, matplotlib"}, true, true);
  return started && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

std::string python_interpreter() {
  static const std::string chosen = [] {
    if (const char* p = std::getenv("GS_PYTHON"); p && *p) return std::string(p);
    const std::string user = on_path("python3");
    if (!user.empty() && python_has_charts(user)) return user;
    std::error_code ec;
    if (std::filesystem::exists("/usr/bin/python3", ec)) return std::string("/usr/bin/python3");
    return user.empty() ? std::string("python3") : user;
  }();
  return chosen;
}

std::string run_process(const std::vector<std::string>& args, bool quiet_stdout,
                        const std::vector<std::string>* environment) {
  if (args.empty()) return "nothing to run";
  const auto [started, status] = spawn_and_wait(args, quiet_stdout, false, environment);
  if (!started) return args[0] + " cannot be started (" + std::strerror(status) + ")";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return args[0] + " was not found";
  if (WIFSIGNALED(status))
    return args[0] + " was stopped by signal " + std::to_string(WTERMSIG(status));
  return args[0] + " exited with " + std::to_string(WEXITSTATUS(status));
}

std::string run_python_module(const std::string& module, const std::vector<std::string>& args,
                              bool quiet_stdout) {
  const std::string dir = find_python_dir(module);
  if (dir.empty())
    return module +
           " not found: the gransim Python package is neither beside the executable, "
           "nor in its install, nor in the source tree it was built from (set "
           "GS_PYTHON_DIR to the folder that holds gransim/)";
  // our environment, the package first on the path; PYTHONSAFEPATH keeps the working
  // directory's files from shadowing the modules the package imports
  std::vector<std::string> env;
  const std::string path_var = "PYTHONPATH=";
  std::string path = path_var + dir;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    if (entry.rfind(path_var, 0) == 0) {
      if (entry.size() > path_var.size()) path += ":" + entry.substr(path_var.size());
    } else if (entry.rfind("PYTHONSAFEPATH=", 0) != 0) {
      env.push_back(entry);
    }
  }
  env.push_back(path);
  env.push_back("PYTHONSAFEPATH=1");

  const std::string py = python_interpreter();
  std::vector<std::string> argv{py, "-m", module};
  argv.insert(argv.end(), args.begin(), args.end());
  const std::string err = run_process(argv, quiet_stdout, &env);
  if (err.empty()) return "";
  if (err.find("cannot be started") != std::string::npos ||
      err.find("not found") != std::string::npos)
    return err + " (set GS_PYTHON to a python3 with numpy and matplotlib)";
  if (!python_has_charts(py))
    return module + " failed: " + py +
           " cannot import numpy and matplotlib (install python3-matplotlib, or set GS_PYTHON "
           "to a python3 that has them)";
  return module + " failed under " + py + " (" + err.substr(py.size() + 1) +
         "; its error is printed above)";
}

}  // namespace gs
