// the value that marks a quantity not measured (too few samples, no fit): NaN in tables, null in
// JSON files
#pragma once
#include <limits>

namespace gs {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace gs
