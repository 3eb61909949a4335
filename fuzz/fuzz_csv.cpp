// libFuzzer target: the CSV readers of `analyze` (taps.csv and plain φ series) and of the RFM
// analysis must turn any bytes into a table or an InputError naming file and line, never a
// crash (tools/fuzz.sh)
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "analysis/rfm_csv.hpp"
#include "analysis/tap_analysis.hpp"
#include "core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::istringstream in(text);
    (void)gs::parse_taps_csv(in, "fuzz_taps.csv");
  } catch (const gs::InputError&) {
  }
  try {
    std::istringstream in(text);
    const gs::rfm::CsvTable t = gs::rfm::parse_csv(in, "fuzz_rfm.csv");
    // every column is as long as the first: the readers index them in parallel
    for (const auto& n : t.names)
      if (t.col(n).size() != t.col(t.names.front()).size()) __builtin_trap();
  } catch (const gs::InputError&) {
  }
  return 0;
}
