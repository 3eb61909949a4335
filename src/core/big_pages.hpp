// large allocations on transparent huge pages: the policy (big_pages.cpp) and the executables'
// global operator new that applies it (global_new/global_new.cpp)
#pragma once
#include <cstddef>

namespace gs {

inline constexpr std::size_t kHugePage = std::size_t{2} << 20;      ///< x86-64's 2 MB page
inline constexpr std::size_t kBigBlockFrom = std::size_t{1} << 20;  ///< 1 MB and more

/// a block of n bytes for free(): 2 MB-aligned and marked for huge pages from kBigBlockFrom
/// on, plain malloc below; nullptr when memory is exhausted
void* big_pages_allocate(std::size_t n) noexcept;

/// does this executable's operator new put large blocks on huge pages? Defined with that
/// operator new (core/global_new/), so only executables that link it can ask; false under the
/// sanitizers, which keep their own
bool big_pages_active();

}  // namespace gs
