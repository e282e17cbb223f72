#include "sim/islands.h"

#include <algorithm>

#include "dynamics/disjoint_sets.h"

namespace polysim::sim {

std::vector<std::vector<int>> findIslands(const std::vector<Eigen::AlignedBox3d>& bounds,
                                          const std::vector<char>& isDynamic,
                                          const std::vector<std::pair<int, int>>& links) {
  const int n = static_cast<int>(bounds.size());
  dynamics::DisjointSets sets(n);
  for (const auto& [i, j] : links)
    if (isDynamic[i] && isDynamic[j]) sets.join(i, j);
  // Sweep along x: bodies sorted by their boxes' lower x, each compared with the ones
  // after it until their lower x passes its upper x.
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (isDynamic[i]) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return bounds[i].min().x() < bounds[j].min().x() || (bounds[i].min().x() == bounds[j].min().x() && i < j);
  });
  for (size_t k = 0; k < order.size(); ++k)
    for (size_t m = k + 1; m < order.size() && bounds[order[m]].min().x() <= bounds[order[k]].max().x(); ++m)
      if (bounds[order[k]].intersects(bounds[order[m]])) sets.join(order[k], order[m]);

  std::vector<std::vector<int>> islands;
  std::vector<int> islandOfRoot(n, -1);
  for (int i = 0; i < n; ++i) {
    if (!isDynamic[i]) continue;
    int& island = islandOfRoot[sets.root(i)];
    if (island < 0) island = static_cast<int>(islands.size()), islands.emplace_back();
    islands[island].push_back(i);
  }
  return islands;
}

}  // namespace polysim::sim
