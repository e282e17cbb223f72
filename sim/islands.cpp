#include "sim/islands.h"

#include <algorithm>

#include "dynamics/disjoint_sets.h"

namespace polysim::sim {

bool pathsMayMeet(const SweptBody& a, const SweptBody& b, double duration, double roundOff) {
  const double apart = (a.velocity - b.velocity).norm() * duration +
                       0.5 * (a.gravity - b.gravity).norm() * duration * duration + a.turn + b.turn;
  return a.start.exteriorDistance(b.start) <= apart + roundOff;
}

SweptBody alongPath(const SweptBody& body, double t, double duration) {
  SweptBody later = body;
  const double turned = duration > 0.0 ? body.turn * t / duration : 0.0;
  later.start.translate(body.velocity * t + 0.5 * body.gravity * t * t);
  later.start = Eigen::AlignedBox3d(later.start.min().array() - turned, later.start.max().array() + turned);
  later.velocity += body.gravity * t;
  later.turn -= turned;
  return later;
}

std::vector<std::vector<int>> findIslands(const std::vector<SweptBody>& bodies, double duration,
                                          const std::vector<std::pair<int, int>>& links, double roundOff) {
  const int n = static_cast<int>(bodies.size());
  dynamics::DisjointSets sets(n);
  for (const auto& [i, j] : links)
    if (bodies[i].dynamic && bodies[j].dynamic) sets.join(i, j);
  // Sweep along x: dynamic bodies sorted by their swept boxes' lower x, each compared
  // with the ones after it until their lower x passes its upper x.
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (bodies[i].dynamic) order.push_back(i);
  const auto lowX = [&](int i) { return bodies[i].swept.min().x(); };
  std::sort(order.begin(), order.end(), [&](int i, int j) { return lowX(i) < lowX(j) || (lowX(i) == lowX(j) && i < j); });
  for (size_t k = 0; k < order.size(); ++k) {
    const SweptBody& a = bodies[order[k]];
    for (size_t m = k + 1; m < order.size() && lowX(order[m]) <= a.swept.max().x(); ++m) {
      const SweptBody& b = bodies[order[m]];
      if (a.swept.intersects(b.swept) && pathsMayMeet(a, b, duration, roundOff)) sets.join(order[k], order[m]);
    }
  }
  std::vector<std::vector<int>> islands;
  std::vector<int> islandOfRoot(n, -1);
  for (int i = 0; i < n; ++i) {
    if (!bodies[i].dynamic) continue;
    int& island = islandOfRoot[sets.root(i)];
    if (island < 0) island = static_cast<int>(islands.size()), islands.emplace_back();
    islands[island].push_back(i);
  }
  return islands;
}

}  // namespace polysim::sim
