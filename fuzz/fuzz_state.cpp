// libFuzzer target: the state-file reader (render, movie) must turn any bytes into particles
// or an InputError naming file and line, never a crash (tools/fuzz.sh)
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "scene/parse.hpp"
#include "sim/state_file.hpp"
#include "world/world.hpp"

namespace {

// two species, so that species names are checked too
const char* kScene = R"([scene]
name = "fuzz"
[model]
kind = "S"
[[material]]
name = "m"
[[species]]
name = "a"
shape = "disk"
radius = 0.001
count = 3
[[species]]
name = "b"
shape = "disk"
radius = 0.002
count = 2
[box]
kind = "periodic"
width = 0.05
[integrator]
kind = "velocity_verlet"
dt = 1e-6
[drive]
kind = "none"
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gs::World base = gs::make_world(gs::parse_scene_string(kScene, "fuzz.toml"));
  gs::World w = base;
  try {
    gs::parse_state_text(w, std::string(reinterpret_cast<const char*>(data), size), "fuzz.csv");
  } catch (const gs::InputError&) {
  }
  return 0;
}
