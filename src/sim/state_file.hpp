// a plain-text state file: enough to restart a picture or a run (not a bitwise checkpoint)
#pragma once
#include <string>

#include "world/world.hpp"

namespace gs {

/// write every particle's species, position, orientation and velocities (17 digits, exact)
void write_state_file(const World& w, const std::string& path);
/// replace the particles of `w` (built from the same scene) with those in the file;
/// InputError naming file and line on a malformed or mismatching file
void read_state_file(World& w, const std::string& path);
/// the same from the file's bytes (`name` for messages)
void parse_state_text(World& w, const std::string& text, const std::string& name);

}  // namespace gs
