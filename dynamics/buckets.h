#pragma once
// Items bucketed by a small integer key (a counting sort), laid out flat: the solver's
// groups of blocks, the bodies each body holds up, the rows of each support level.

#include <vector>

namespace polysim::dynamics {

/// Items 0 .. keys.size() - 1, each in the bucket keys[i] (0 <= key < bucketCount; a
/// negative key leaves its item out). Bucket b holds items[start[b], start[b + 1]), in
/// increasing order: the sort is stable, so buckets keep the order the items came in.
struct Buckets {
  std::vector<int> start;  // bucketCount + 1 entries
  std::vector<int> items;

  Buckets(int bucketCount, const std::vector<int>& keys) : start(static_cast<size_t>(bucketCount) + 1, 0) {
    for (int key : keys)
      if (key >= 0) ++start[static_cast<size_t>(key) + 1];
    for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    items.resize(static_cast<size_t>(start.back()));
    std::vector<int> next(start.begin(), start.end() - 1);
    for (int i = 0; i < static_cast<int>(keys.size()); ++i)
      if (keys[i] >= 0) items[static_cast<size_t>(next[static_cast<size_t>(keys[i])]++)] = i;
  }

  int bucketCount() const { return static_cast<int>(start.size()) - 1; }
  const int* begin(int b) const { return items.data() + start[static_cast<size_t>(b)]; }
  const int* end(int b) const { return items.data() + start[static_cast<size_t>(b) + 1]; }
  bool empty(int b) const { return start[static_cast<size_t>(b)] == start[static_cast<size_t>(b) + 1]; }
};

}  // namespace polysim::dynamics
