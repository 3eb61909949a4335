// Large blocks on transparent huge pages. Debian's kernels hand 2 MB pages only to memory that
// asks for them (/sys/kernel/mm/transparent_hugepage/enabled = madvise), and glibc's malloc
// does not ask unless GLIBC_TUNABLES says so. A large scene's state (10⁶ disks: some twenty
// arrays of 8 MB, read in passes and in the neighbours' order) then needs a 4 KB page entry
// for every 4 KB it touches, far more than the TLB holds. So every C++ allocation of 1 MB or
// more (the state's and the contact model's vectors) is aligned to 2 MB and marked
// MADV_HUGEPAGE; smaller ones are plain malloc. Where the kernel has no huge pages the mark is
// ignored and nothing changes. Every block is freed by free(), whichever way it came.
// The sanitizer builds keep their own operator new (it checks new/delete pairs).
#include "core/big_pages.hpp"

#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define GS_BIG_PAGES 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define GS_BIG_PAGES 0
#endif
#endif
#ifndef GS_BIG_PAGES
#define GS_BIG_PAGES 1
#endif

namespace gs {

bool big_pages_active() { return GS_BIG_PAGES != 0; }

}  // namespace gs

#if GS_BIG_PAGES
namespace {

void* allocate(std::size_t n) noexcept {
  if (n >= gs::kBigBlockFrom) {
    const std::size_t m = (n + gs::kHugePage - 1) / gs::kHugePage * gs::kHugePage;
    if (void* p = std::aligned_alloc(gs::kHugePage, m)) {
      madvise(p, m, MADV_HUGEPAGE);  // a hint: refused (no THP), the block is still good
      return p;
    }
  }
  return std::malloc(n == 0 ? 1 : n);
}

// operator new's contract: retry through the new-handler, else std::bad_alloc
void* allocate_or_throw(std::size_t n) {
  for (;;) {
    if (void* p = allocate(n)) return p;
    const std::new_handler h = std::get_new_handler();
    if (h == nullptr) throw std::bad_alloc();
    h();
  }
}

}  // namespace

void* operator new(std::size_t n) { return allocate_or_throw(n); }
void* operator new[](std::size_t n) { return allocate_or_throw(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#endif
