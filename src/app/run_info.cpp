#include "app/run_info.hpp"

#include <toml++/toml.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace gs {

namespace fs = std::filesystem;

std::optional<std::string> read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

// a top-level value of a parsed JSON text; nullopt when the key is absent
std::optional<nlohmann::json> top_level(const nlohmann::json& j, const std::string& key) {
  if (!j.is_object() || !j.contains(key)) return std::nullopt;
  return j.at(key);
}

nlohmann::ordered_json from_toml(const toml::node& n) {
  if (auto v = n.as_integer()) return v->get();
  if (auto v = n.as_floating_point()) return v->get();
  if (auto v = n.as_boolean()) return v->get();
  if (auto v = n.as_string()) return v->get();
  if (auto a = n.as_array()) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const auto& e : *a) out.push_back(from_toml(e));
    return out;
  }
  if (auto t = n.as_table()) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const auto& [k, v] : *t) out[std::string(k.str())] = from_toml(v);
    return out;
  }
  return nullptr;  // dates and times: no scene key has one
}

}  // namespace

nlohmann::ordered_json scene_json(const std::map<std::string, std::string>& resolved) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const auto& [k, v] : resolved) {
    try {
      const toml::table t = toml::parse("v = " + v);
      out[k] = from_toml(*t.get("v"));
    } catch (const toml::parse_error&) {
      out[k] = v;  // not TOML value text: kept as written
    }
  }
  return out;
}

// the text after `"key": ` at the top level (run.json puts top-level keys at two spaces)
static std::optional<std::size_t> field_start(const std::string& json, const std::string& key) {
  const std::string pat = "\n  \"" + key + "\": ";
  const std::size_t p = json.find(pat);
  if (p == std::string::npos) return std::nullopt;
  return p + pat.size();
}

std::optional<std::string> json_string_field(const std::string& json, const std::string& key) {
  // files that are not JSON (run.json written with nan or inf) are scanned line by line
  if (const nlohmann::json j = nlohmann::json::parse(json, nullptr, false); !j.is_discarded()) {
    const auto v = top_level(j, key);
    if (v && v->is_string()) return v->get<std::string>();
    return std::nullopt;
  }
  const auto p = field_start(json, key);
  if (!p || *p >= json.size() || json[*p] != '"') return std::nullopt;
  std::string v;
  for (std::size_t i = *p + 1; i < json.size(); ++i) {
    if (json[i] == '\\' && i + 1 < json.size()) {
      v += json[++i];
      continue;
    }
    if (json[i] == '"') return v;
    v += json[i];
  }
  return std::nullopt;
}

std::optional<double> json_number_field(const std::string& json, const std::string& key) {
  // files that are not JSON (run.json written with nan or inf) are scanned line by line
  if (const nlohmann::json j = nlohmann::json::parse(json, nullptr, false); !j.is_discarded()) {
    const auto v = top_level(j, key);
    if (v && v->is_number()) return v->get<double>();
    // nlohmann-json writes a non-finite number as null
    if (v && v->is_null()) return std::numeric_limits<double>::quiet_NaN();
    return std::nullopt;
  }
  const auto p = field_start(json, key);
  if (!p) return std::nullopt;
  const char* b = json.c_str() + *p;
  char* e = nullptr;
  const double v = std::strtod(b, &e);
  if (e == b) return std::nullopt;
  return v;
}

std::string run_status(const std::string& dir) {
  const auto text = read_text_file(dir + "/run.json");
  if (!text) return "";
  return json_string_field(*text, "status").value_or("unknown");
}

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
