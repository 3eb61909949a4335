// run the gransim binary from a test: fork/exec with arguments and extra environment, stdout
// and stderr into one log file; optionally send a signal after a delay (kill-and-resume tests)
#pragma once
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace gs::testing {

struct Outcome {
  bool exited = false;  ///< false: ended by a signal (crash, the alarm, or the test's kill)
  int code = -1;        ///< exit code, or the signal number
  std::string output;   ///< stdout and stderr together
};

struct Launch {
  std::vector<std::string> env;  ///< "NAME=value" added to the environment
  int alarm_s = 30;              ///< SIGALRM after this long (stops hangs)
  /// SIGXCPU after this much CPU time (−1: none): a bound on work that a busy machine does not
  /// stretch, unlike alarm_s
  int cpu_limit_s = -1;
  double signal_after_s = -1.0;  ///< send `signal` after this many seconds (−1: never)
  /// send `signal` once this returns true (polled every 5 ms; wins over signal_after_s): an
  /// observed event such as a checkpoint file appearing, robust on a loaded machine
  std::function<bool()> signal_when;
  int signal = SIGKILL;
  long file_size_limit = -1;  ///< RLIMIT_FSIZE in bytes (a full disk for every file); −1 none
};

inline Outcome run_binary(const std::vector<std::string>& args, const std::filesystem::path& log,
                          const Launch& how = {}) {
  std::vector<std::string> a = args;
  std::string bin = GS_BINARY;
  std::vector<char*> argv{bin.data()};
  for (std::string& s : a) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::vector<std::string> env = how.env;
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    for (std::string& e : env) ::putenv(e.data());
    ::alarm(static_cast<unsigned>(how.alarm_s));
    if (how.cpu_limit_s >= 0) {
      const rlimit cpu{static_cast<rlim_t>(how.cpu_limit_s), static_cast<rlim_t>(how.cpu_limit_s)};
      ::setrlimit(RLIMIT_CPU, &cpu);
    }
    if (how.file_size_limit >= 0) {
      // writes past the limit fail with EFBIG instead of killing the process
      ::signal(SIGXFSZ, SIG_IGN);
      const rlimit lim{static_cast<rlim_t>(how.file_size_limit),
                       static_cast<rlim_t>(how.file_size_limit)};
      ::setrlimit(RLIMIT_FSIZE, &lim);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  if (how.signal_when) {
    while (!how.signal_when()) {
      if (::waitpid(pid, &status, WNOHANG) == pid) goto done;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ::kill(pid, how.signal);
  } else if (how.signal_after_s >= 0) {
    const auto until =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(how.signal_after_s);
    while (std::chrono::steady_clock::now() < until) {
      if (::waitpid(pid, &status, WNOHANG) == pid) goto done;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ::kill(pid, how.signal);
  }
  ::waitpid(pid, &status, 0);
done:
  Outcome o;
  o.exited = WIFEXITED(status);
  o.code = o.exited ? WEXITSTATUS(status) : WTERMSIG(status);
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  o.output = ss.str();
  return o;
}

/// a shell command line's exit code and output (stdout and stderr together)
struct ShellResult {
  int code = -1;
  std::string output;
};

inline ShellResult sh(const std::string& cmd) {
  ShellResult r;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) r.output += buf;
  const int st = pclose(p);
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// a whole file's bytes ("" if it cannot be read)
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// the command line that runs gransim with `args` (the Python package of this source tree)
inline std::string gransim(const std::string& args) {
  return std::string("GS_PYTHON_DIR=") + GS_SOURCE_DIR + "/python " + GS_BINARY + " " + args;
}

/// a 40-grain tapping pile in a 0.1 m box (velocity Verlet at 1e-4 s, T = 0.5 s, 0.01 s
/// pulses of g_p = 2): a few seconds per run
inline std::string tiny_tapping_scene(int taps) {
  return R"(
[scene]
name = "tiny_tapping"
[[material]]
name = "grain"
[[species]]
name = "big"
radius = 0.009
count = 18
[[species]]
name = "small"
radius = 0.00636
count = 22
[box]
width = 0.1
height = 0.5
[preparation]
seed = 5
settle_time = 0.5
[integrator]
kind = "velocity_verlet"
dt = 1e-4
[drive]
kind = "negative_g"
g_p = 2.0
t1 = 0.01
period = 0.5
taps = )" +
         std::to_string(taps) +
         R"(
[output]
test_rect = [0.01, 0.01, 0.09, 0.05]
discard_taps = 2
series_every = 500
)";
}

/// an event to send a signal on (Launch::signal_when): a checkpoint in DIR that was not there
/// when this was called (a resumed run's own first checkpoint, not its predecessor's)
inline std::function<bool()> new_checkpoint_in(const std::filesystem::path& dir) {
  auto names = [dir] {
    std::set<std::string> out;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
      if (e.path().extension() == ".gsck") out.insert(e.path().filename().string());
    return out;
  };
  const std::set<std::string> before = names();
  return [names, before] {
    for (const std::string& n : names())
      if (!before.count(n)) return true;
    return false;
  };
}

/// a fresh empty directory for the running gtest test: <tmp>/<prefix>_<pid>_<test name>
inline std::filesystem::path fresh_test_dir(const std::string& prefix) {
  namespace fs = std::filesystem;
  const char* test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path d =
      fs::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()) + "_" + test);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace gs::testing
