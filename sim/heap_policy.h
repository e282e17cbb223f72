#pragma once
// How the process's allocator hands memory back to the system: for a program, not the
// library (polysim's main and the benchmarks' call it first thing).

namespace polysim::sim {

/// Keeps the memory the process frees for its next allocations (glibc's malloc): blocks of
/// up to 32 MiB come from the heap instead of their own mappings, and the heap's free top
/// is not handed back until it passes 1 GiB. A step allocates and frees megabytes (the
/// solver's rows, shock propagation's levels, the contact lists); by default glibc returns
/// much of it at once and each next solve faults it back in, page by page: the pile of
/// 1000's first 3 s took 58,000 page faults and 0.8 s of system time (`/usr/bin/time -v`),
/// against 8,200 and 0.3 s with this. The price: the heap stays at its peak (that pile's
/// peak resident memory 38.9 MB against 36.9). Returns false where it does not apply
/// (another allocator, or one a sanitizer put in glibc's place), changing nothing then.
bool keepFreedMemory();

}  // namespace polysim::sim
