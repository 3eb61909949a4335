// The gransim executable's global operator new and delete: large blocks on huge pages
// (core/big_pages.cpp says why). Linked into executables only, so a host process that loads the
// library (the Python interpreter) keeps its own allocator. The sanitizer builds keep theirs
// (it checks new/delete pairs).
#include <cstddef>
#include <cstdlib>
#include <new>

#include "core/big_pages.hpp"

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

// operator new's contract: retry through the new-handler, else std::bad_alloc
void* allocate_or_throw(std::size_t n) {
  for (;;) {
    if (void* p = gs::big_pages_allocate(n)) return p;
    const std::new_handler h = std::get_new_handler();
    if (h == nullptr) throw std::bad_alloc();
    h();
  }
}

}  // namespace

void* operator new(std::size_t n) { return allocate_or_throw(n); }
void* operator new[](std::size_t n) { return allocate_or_throw(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return gs::big_pages_allocate(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return gs::big_pages_allocate(n);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#endif
