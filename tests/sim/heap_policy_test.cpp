// The heap policy of polysim's main and the benchmarks (sim/heap_policy.h).

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>  // defines __GLIBC__ where glibc is the C library
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "sim/heap_policy.h"

namespace polysim::sim {
namespace {

// A block as large as a pile's solve allocates (16 MiB) comes from the heap, not a
// mapping of its own, and once freed stays with the process for the next solve: glibc's
// defaults map it (over 128 KiB) and hand it back, and the next one faults in afresh.
TEST(HeapPolicy, ABlockOfMegabytesFreedStaysWithTheProcess) {
#if defined(__GLIBC__)
  if (!keepFreedMemory()) GTEST_SKIP() << "not glibc's own allocator (a sanitizer's)";
  constexpr size_t kBlock = size_t{16} << 20;
  const size_t mappedBefore = mallinfo2().hblkhd;
  {
    const std::vector<char> block(kBlock, 1);
    EXPECT_EQ(mallinfo2().hblkhd, mappedBefore) << "the block has a mapping of its own";
  }
  EXPECT_GE(mallinfo2().fordblks, kBlock) << "the freed block went back to the system";
#else
  EXPECT_FALSE(keepFreedMemory());  // nothing to set outside glibc
#endif
}

}  // namespace
}  // namespace polysim::sim
