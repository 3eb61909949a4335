// large allocations on transparent huge pages (big_pages.cpp replaces the global operator new)
#pragma once
#include <cstddef>

namespace gs {

inline constexpr std::size_t kHugePage = std::size_t{2} << 20;      ///< x86-64's 2 MB page
inline constexpr std::size_t kBigBlockFrom = std::size_t{1} << 20;  ///< 1 MB and more

/// does this build's operator new put large blocks on huge pages? (not under the sanitizers)
bool big_pages_active();

}  // namespace gs
