// what a finished (or unfinished) run directory says about itself: its run.json status and
// fields (read with nlohmann-json; older files with bare non-finite numbers read them as null)
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace gs {

/// the whole text of a small file; nullopt when it cannot be read
std::optional<std::string> read_text_file(const std::string& path);

/// the value of a top-level string field "key": "value" of run.json text; nullopt if absent
std::optional<std::string> json_string_field(const std::string& json, const std::string& key);
/// the value of a top-level number field "key": 1.5 of run.json text; nullopt if absent
std::optional<double> json_number_field(const std::string& json, const std::string& key);

/// the resolved scene (dotted key → TOML value text) as typed JSON values: numbers, booleans,
/// strings, arrays, inline tables as objects
nlohmann::ordered_json scene_json(const std::map<std::string, std::string>& resolved);

/// DIR/run.json's status ("completed", "interrupted", "unstable"); "" when there is no run.json
std::string run_status(const std::string& dir);

}  // namespace gs
