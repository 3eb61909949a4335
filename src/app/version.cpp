#include "app/version.hpp"
namespace gs {
std::string_view program_version() { return GS_VERSION; }
}  // namespace gs
