#include "app/locations.hpp"

#include <cstdlib>
#include <filesystem>

#ifndef GS_PYTHON_INSTALL_DIR
#define GS_PYTHON_INSTALL_DIR "lib/python3/dist-packages"
#endif

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

std::string find_python_dir(const std::string& module) {
  // gransim.charts.tapping: gransim/charts/tapping.py, or a package's gransim/reproduce/__init__.py
  std::string rel = module;
  for (char& c : rel)
    if (c == '.') c = '/';
  std::error_code ec;
  const auto holds = [&](const fs::path& d) {
    return fs::exists(d / (rel + ".py"), ec) || fs::exists(d / rel / "__init__.py", ec);
  };
  if (const char* env = std::getenv("GS_PYTHON_DIR"); env && *env)
    return holds(env) ? std::string(env) : std::string();
  const fs::path exe_dir = fs::path(self_executable()).parent_path();
  // a build tree (its copy of the package), then an install
  for (const fs::path& d : {exe_dir / "python", exe_dir / ".." / GS_PYTHON_INSTALL_DIR})
    if (holds(d)) return fs::weakly_canonical(d, ec).string();
#ifdef GS_SOURCE_DIR_OF_BUILD
  const fs::path source = fs::path(GS_SOURCE_DIR_OF_BUILD) / "python";
  if (holds(source)) return source.string();
#endif
  return "";
}

}  // namespace gs
