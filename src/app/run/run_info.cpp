#include "app/run/run_info.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "output/json_text.hpp"

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

std::optional<std::string> json_string_field(const std::string& json, const std::string& key) {
  const nlohmann::json j = parse_json_lenient(json);
  const auto v = top_level(j, key);
  if (v && v->is_string()) return v->get<std::string>();
  return std::nullopt;
}

std::optional<double> json_number_field(const std::string& json, const std::string& key) {
  const nlohmann::json j = parse_json_lenient(json);
  const auto v = top_level(j, key);
  if (v && v->is_number()) return v->get<double>();
  // a non-finite number is written as null
  if (v && v->is_null()) return std::numeric_limits<double>::quiet_NaN();
  return std::nullopt;
}

std::string run_status(const std::string& dir) {
  const auto text = read_text_file(dir + "/run.json");
  if (!text) return "";
  return json_string_field(*text, "status").value_or("unknown");
}

}  // namespace gs
