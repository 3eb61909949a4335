// libFuzzer target: the scene parser must turn any bytes into a SceneSpec or an InputError,
// never a crash, a hang or undefined behaviour (build and run: tools/fuzz.sh)
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.hpp"
#include "scene/parse.hpp"

// every input is a scene file; a SceneSpec that parses must also write back and re-parse
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const gs::SceneSpec s = gs::parse_scene_string(text, "fuzz.toml");
    (void)gs::parse_scene_string(gs::scene_to_toml(s), "fuzz-roundtrip.toml");
  } catch (const gs::InputError&) {
    // the expected outcome for bad input
  }
  return 0;
}
