// a plain-text state file: enough to restart a picture or a run (not a bitwise checkpoint).
// STATE.csv holds one row per grain under a plain header (pandas reads it as it is); its time
// and step go to STATE.json beside it. Files with the older "# gransim state v1" preamble are
// read too.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "world/world.hpp"

namespace gs {

/// the grains of a state file, in its row order (particle label order)
struct StateRows {
  std::vector<std::string> species;  ///< species name of each grain
  std::vector<int> line;             ///< line of each grain in the file, for messages
  std::vector<double> x, y, th, vx, vy, omega;
  double t = 0.0;         ///< simulated time of the state (0 when not recorded), s
  std::int64_t step = 0;  ///< step of the state (0 when not recorded)
  std::size_t size() const { return x.size(); }
};

/// the sidecar of a state file: STATE.csv → STATE.json
std::string state_sidecar_path(const std::string& csv_path);

/// write every particle's species, position, orientation and velocities (17 digits, exact)
/// and, beside it, the sidecar with t, step and the particle count
void write_state_file(const World& w, const std::string& path);
/// read a state file (either form); InputError naming file and line when it is malformed
StateRows read_state_rows(const std::string& path);
/// replace the particles of `w` (built from the same scene) with those in the file;
/// InputError naming file and line on a malformed or mismatching file
void read_state_file(World& w, const std::string& path);
/// the same from the file's bytes (`name` for messages)
void parse_state_text(World& w, const std::string& text, const std::string& name);

}  // namespace gs
