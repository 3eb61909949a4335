// the replaced operator new (core/big_pages.cpp): blocks of 1 MB and more start on a 2 MB
// boundary and are marked for transparent huge pages (the kernel's smaps then calls their
// mapping THP-eligible); the standard's failure forms still hold
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <new>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "core/big_pages.hpp"

namespace gs {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// the "THPeligible:" value of the mapping that holds address p, or -1 where smaps has none
int thp_eligible(const void* p) {
  std::ifstream in("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    unsigned long lo = 0, hi = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = a >= lo && a < hi;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

TEST(BigPages, LargeBlocksStartOnAHugePageAndAreMarked) {
  if (!big_pages_active()) GTEST_SKIP() << "sanitizer build: its own operator new";
  const std::string thp = read_file("/sys/kernel/mm/transparent_hugepage/enabled");
  for (std::size_t bytes : {kBigBlockFrom, 3 * kHugePage + 8, std::size_t{64} << 20}) {
    std::vector<double> v(bytes / sizeof(double), 1.5);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % kHugePage, 0u) << bytes;
    // usable to its last element
    EXPECT_EQ(std::accumulate(v.begin(), v.end(), 0.0), 1.5 * static_cast<double>(v.size()));
    if (!thp.empty() && thp.find("[never]") == std::string::npos) {
      const int e = thp_eligible(v.data());
      if (e >= 0) {
        EXPECT_EQ(e, 1) << bytes << " bytes; THP setting: " << thp;
      }
    }
  }
}

TEST(BigPages, StandardFormsAndFailures) {
  // the array and nothrow forms take the same way
  double* a = new double[kBigBlockFrom / sizeof(double)];
  if (big_pages_active()) {
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a) % kHugePage, 0u);
  }
  a[kBigBlockFrom / sizeof(double) - 1] = 2.0;
  delete[] a;
  void* p = ::operator new(kBigBlockFrom + 1, std::nothrow);
  ASSERT_NE(p, nullptr);
  if (big_pages_active()) {
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kHugePage, 0u);
  }
  ::operator delete(p, std::nothrow);
  // small blocks, and zero bytes: distinct, usable pointers
  void* z0 = ::operator new(0);
  void* z1 = ::operator new(0);
  EXPECT_NE(z0, z1);
  ::operator delete(z0);
  ::operator delete(z1);
  // a request no machine can meet: std::bad_alloc, or nullptr from the nothrow form (ours:
  // AddressSanitizer's operator new aborts on it unless allocator_may_return_null is set)
  if (!big_pages_active()) return;
  const std::size_t absurd = std::size_t{1} << 62;
  EXPECT_THROW(static_cast<void>(::operator new(absurd)), std::bad_alloc);
  EXPECT_EQ(::operator new(absurd, std::nothrow), nullptr);
}

}  // namespace
}  // namespace gs
