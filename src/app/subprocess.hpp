// child processes of the application, every one started here: the charts and the report of the
// gransim Python package (python3 -m gransim.…), and a sweep's runs (this binary again, its
// output into a log file)
#pragma once
#include <sys/types.h>

#include <string>
#include <vector>

namespace gs {

/// where a child's standard streams go and what environment it gets
struct ChildSetup {
  bool stdin_null = false;    ///< read from /dev/null (else ours)
  bool quiet_stdout = false;  ///< standard output to /dev/null
  bool quiet_stderr = false;  ///< standard error to /dev/null
  std::string log;            ///< when set: standard output and error into this file
  bool append_log = false;    ///< append to `log` (else truncate it)
  /// the environment as NAME=value entries; null: ours
  const std::vector<std::string>* environment = nullptr;
};

/// start argv[0] (looked up on PATH unless it holds a '/') with argv, without waiting; its
/// process id. Throws std::runtime_error naming the program when it cannot be started.
pid_t start_process(const std::vector<std::string>& argv, const ChildSetup& setup);

/// the interpreter for the Python package's charts and report: $GS_PYTHON; else `python3` on
/// PATH when it imports numpy and matplotlib (the user's own environment); else
/// /usr/bin/python3 (Debian's, where python3-matplotlib installs them); else `python3`. Decided
/// once per process.
std::string python_interpreter();

/// whether `python` imports numpy and matplotlib (runs it once, silently)
bool python_has_charts(const std::string& python);

/// run argv[0] (looked up on PATH) with argv and wait; returns "" when it exited 0, else a
/// sentence saying what went wrong (cannot be started, not found, its exit code). With
/// `quiet_stdout` the child's standard output goes to /dev/null (its errors still show);
/// `environment` (NAME=value entries) replaces ours when given.
std::string run_process(const std::vector<std::string>& argv, bool quiet_stdout = false,
                        const std::vector<std::string>* environment = nullptr);

/// run `python3 -m module args` for a module of the gransim Python package
/// (gransim.charts.tapping, gransim.reproduce) under python_interpreter(), the package's folder
/// (find_python_dir) first on PYTHONPATH; "" on success, else a sentence naming the module and
/// the interpreter, and the missing libraries only when they are missing
std::string run_python_module(const std::string& module, const std::vector<std::string>& args,
                              bool quiet_stdout = false);

}  // namespace gs
