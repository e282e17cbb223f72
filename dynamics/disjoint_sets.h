#pragma once
// Disjoint sets (union-find) over 0..n-1, for grouping bodies that are linked, directly or
// through a chain: islands of a step, groups of contacts that a solve may sweep apart.

#include <algorithm>
#include <numeric>
#include <vector>

namespace polysim::dynamics {

/// Union-find with path halving. The root of a set is its smallest member, so that
/// groups built from it come out in a fixed order.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int root(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(int i, int j) {
    i = root(i), j = root(j);
    if (i != j) parent_[std::max(i, j)] = std::min(i, j);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace polysim::dynamics
