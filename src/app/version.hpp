#pragma once
#include <string>
#include <string_view>
namespace gs {
/// the program version (CMake project version)
std::string_view program_version();
/// what `gransim --version` prints: version, the commit built from, the enabled features
std::string version_text();
}  // namespace gs
