// where this program and the files shipped with it (tools/, scenes/) are
#pragma once
#include <string>

namespace gs {

/// the gransim executable of this process (/proc/self/exe)
std::string self_executable();

/// the shipped folder `folder` (tools, scenes) that holds `file`: <dir of the executable>/../F,
/// <dir>/F, <dir>/../share/gransim/F (an install), else the source tree the binary was built
/// from; "" when none holds it
std::string find_data_dir(const std::string& folder, const std::string& file);

/// the folder of helper scripts: $GS_TOOLS_DIR, else find_data_dir("tools", script)
std::string find_tools_dir(const std::string& script);

}  // namespace gs
