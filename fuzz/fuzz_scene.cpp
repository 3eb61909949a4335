// libFuzzer target: the scene parser must turn any bytes into a SceneSpec or an InputError,
// never a crash, a hang or undefined behaviour (build and run: tools/fuzz.sh)
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "core/error.hpp"
#include "scene/parse.hpp"

// every input is a scene file; a SceneSpec that parses must also write back and re-parse.
// The round trip sits outside the catch for bad input: its failure is a finding, not bad input
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  gs::SceneSpec s;
  try {
    s = gs::parse_scene_string(text, "fuzz.toml");
  } catch (const gs::InputError&) {
    return 0;  // the expected outcome for bad input
  }
  const std::string back = gs::scene_to_toml(s);
  try {
    (void)gs::parse_scene_string(back, "fuzz-roundtrip.toml");
  } catch (const gs::InputError& e) {
    std::fprintf(stderr, "an accepted scene does not re-parse after scene_to_toml: %s\n%s\n",
                 e.what(), back.c_str());
    std::abort();
  }
  return 0;
}
