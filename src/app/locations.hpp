// where this program and the files shipped with it (scenes/, shaders/, the Python package) are
#pragma once
#include <string>

namespace gs {

/// the gransim executable of this process (/proc/self/exe)
std::string self_executable();

/// the shipped folder `folder` (scenes, shaders) that holds `file`: <dir of the executable>/../F,
/// <dir>/F, <dir>/../share/gransim/F (an install), else the source tree the binary was built
/// from; "" when none holds it
std::string find_data_dir(const std::string& folder, const std::string& file);

/// the folder to put on PYTHONPATH for `module` of the gransim Python package (dotted:
/// gransim.charts.tapping): $GS_PYTHON_DIR, else <dir of the executable>/python (a build
/// tree), <dir>/../lib/python3/dist-packages (an install), else the source tree's python/;
/// "" when none holds the module
std::string find_python_dir(const std::string& module);

}  // namespace gs
