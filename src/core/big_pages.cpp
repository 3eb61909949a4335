// Large blocks on transparent huge pages. Debian's kernels hand 2 MB pages only to memory that
// asks for them (/sys/kernel/mm/transparent_hugepage/enabled = madvise), and glibc's malloc
// does not ask unless GLIBC_TUNABLES says so. A large scene's state (10⁶ disks: some twenty
// arrays of 8 MB, read in passes and in the neighbours' order) then needs a 4 KB page entry
// for every 4 KB it touches, far more than the TLB holds. So the gransim executable's operator
// new (core/global_new/, linked into executables only, never into a library that a host process
// such as Python loads) aligns every block of 1 MB or more to 2 MB and marks it MADV_HUGEPAGE;
// smaller ones are plain malloc. Where the kernel has no huge pages the mark is ignored and
// nothing changes. Every block is freed by free(), whichever way it came.
#include "core/big_pages.hpp"

#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>

namespace gs {

void* big_pages_allocate(std::size_t n) noexcept {
  if (n >= kBigBlockFrom) {
    const std::size_t m = (n + kHugePage - 1) / kHugePage * kHugePage;
    if (void* p = std::aligned_alloc(kHugePage, m)) {
      madvise(p, m, MADV_HUGEPAGE);  // a hint: refused (no THP), the block is still good
      return p;
    }
  }
  return std::malloc(n == 0 ? 1 : n);
}

}  // namespace gs
