// scene files (TOML) → SceneSpec, and back. The format is documented key by key in
// docs/scene-format.md; every error is an InputError naming file:line, the dotted key,
// what is wrong and what is accepted.
#pragma once
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "scene/spec.hpp"

namespace gs {

/// parse and validate a scene file; overrides are "dotted.key=value" strings (value in TOML
/// syntax, e.g. "drive.g_p=8", "integrator.kind=\"velocity_verlet\"", or bare words accepted
/// as strings) applied before validation. Throws InputError naming file, line and key.
SceneSpec parse_scene_file(const std::string& path, const std::vector<std::string>& overrides = {});

/// the same for scene text already in memory; name_for_messages stands in for the file name
SceneSpec parse_scene_string(std::string_view toml, const std::string& name_for_messages,
                             const std::vector<std::string>& overrides = {});

/// a complete TOML scene equivalent to s: parse_scene_string(scene_to_toml(s)) gives back s
/// (apart from path, line numbers and resolved)
std::string scene_to_toml(const SceneSpec& s);

/// every key path of s with its value as TOML text ("species[0].radius" → "0.009"),
/// defaults included; parse_scene_* stores this in SceneSpec::resolved
std::map<std::string, std::string> scene_resolved(const SceneSpec& s);

}  // namespace gs
