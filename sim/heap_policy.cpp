#include "sim/heap_policy.h"

#include <cstdlib>  // any C library header: it defines __GLIBC__ where glibc is the C library

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace polysim::sim {

bool keepFreedMemory() {
#if defined(__GLIBC__)
  // Set both: setting either turns off glibc's own adjustment of both (a trim threshold
  // alone left every block over 128 KiB in a mapping of its own: four times the faults).
  // 32 MiB is the largest mapping threshold glibc accepts on 64-bit systems.
  constexpr int kMapAbove = 32 << 20;
  constexpr int kTrimAbove = 1 << 30;
  return mallopt(M_MMAP_THRESHOLD, kMapAbove) == 1 && mallopt(M_TRIM_THRESHOLD, kTrimAbove) == 1;
#else
  return false;
#endif
}

}  // namespace polysim::sim
