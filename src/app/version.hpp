#pragma once
#include <string_view>
namespace gs {
/// the program version (CMake project version)
std::string_view program_version();
}  // namespace gs
