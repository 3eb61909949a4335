// libFuzzer target: the checkpoint decoder must turn any bytes into a Checkpoint or an
// InputError naming the byte offset, never a crash or a huge allocation (tools/fuzz.sh).
// FUZZ_CHECKSUM=0 (the default) lets mutated payloads past the checksum so the field
// decoders behind it are reached: the target reseals every input before decoding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "sim/checkpoint.hpp"

// fix the payload size and checksum of inputs long enough to have a header
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

// each input is tried as it is and resealed
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string raw(reinterpret_cast<const char*>(data), size);
  for (const std::string& b : {raw, reseal(raw)}) {
    try {
      (void)gs::decode_checkpoint(b, "fuzz.gsck");
    } catch (const gs::InputError&) {
    }
  }
  return 0;
}
