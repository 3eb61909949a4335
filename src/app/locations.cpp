#include "app/locations.hpp"

#include <cstdlib>
#include <filesystem>

namespace gs {

namespace fs = std::filesystem;

std::string self_executable() {
  std::error_code ec;
  std::string p = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) return "gransim";
  // a rebuilt binary replaces the file: the link then reads "<path> (deleted)"
  const std::string deleted = " (deleted)";
  if (p.size() > deleted.size() &&
      p.compare(p.size() - deleted.size(), deleted.size(), deleted) == 0)
    p.resize(p.size() - deleted.size());
  return p;
}

std::string find_data_dir(const std::string& folder, const std::string& file) {
  std::error_code ec;
  const fs::path exe_dir = fs::path(self_executable()).parent_path();
  for (const fs::path& d :
       {exe_dir / ".." / folder, exe_dir / folder, exe_dir / ".." / "share" / "gransim" / folder})
    if (fs::exists(d / file, ec)) return fs::weakly_canonical(d, ec).string();
#ifdef GS_SOURCE_DIR_OF_BUILD
  // a build tree outside the sources (cmake -S . -B ../build) has nothing beside it
  const fs::path source = fs::path(GS_SOURCE_DIR_OF_BUILD) / folder;
  if (fs::exists(source / file, ec)) return source.string();
#endif
  return "";
}

std::string find_tools_dir(const std::string& script) {
  std::error_code ec;
  if (const char* env = std::getenv("GS_TOOLS_DIR"); env && *env)
    return fs::exists(fs::path(env) / script, ec) ? std::string(env) : std::string();
  return find_data_dir("tools", script);
}

}  // namespace gs
