// libFuzzer target: a checkpoint that decodes must restore into a Simulation or be refused
// with an InputError naming the file (restore_simulation checks species, finiteness, the
// integrator and its history), never a crash (tools/fuzz.sh). Inputs are resealed, so the
// mutations reach the fields behind the checksum.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "sim/checkpoint.hpp"
#include "sim/simulation.hpp"

static std::string reseal(std::string b) {
  if (b.size() < gs::kCheckpointHeader) return b;
  const std::uint64_t size = b.size() - gs::kCheckpointHeader;
  const std::uint64_t sum = gs::fnv1a64(std::string_view(b).substr(gs::kCheckpointHeader));
  for (int k = 0; k < 8; ++k) {
    b[16 + k] = static_cast<char>(size >> (8 * k));
    b[24 + k] = static_cast<char>(sum >> (8 * k));
  }
  return b;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string raw = reseal(std::string(reinterpret_cast<const char*>(data), size));
  gs::Checkpoint c;
  try {
    c = gs::decode_checkpoint(raw, "fuzz.gsck");
  } catch (const gs::InputError&) {
    return 0;
  }
  // a huge but well-formed particle count would only measure the allocator
  if (c.sp.size() > 5000) return 0;
  try {
    gs::Simulation sim = gs::restore_simulation(c);
    (void)sim;
  } catch (const gs::InputError&) {
  }
  return 0;
}
