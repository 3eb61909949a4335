// child processes of the application: the Python chart and report scripts
#pragma once
#include <string>
#include <vector>

namespace gs {

/// the interpreter for the scripts: $GS_PYTHON, else /usr/bin/python3 (where Debian's numpy
/// and matplotlib live), else python3 on PATH
std::string python_interpreter();

/// run argv[0] (looked up on PATH) with argv and wait; returns "" when it exited 0, else a
/// sentence saying what went wrong (cannot be started, not found, its exit code)
std::string run_process(const std::vector<std::string>& argv);

}  // namespace gs
