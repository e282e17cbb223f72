// findIslands(): which bodies must step through their contact events together.

#include "sim/islands.h"

#include <gtest/gtest.h>

namespace polysim::sim {
namespace {

Eigen::AlignedBox3d unitBoxAt(double x, double y = 0.0) {
  return Eigen::AlignedBox3d(Eigen::Vector3d(x - 0.5, y - 0.5, 0), Eigen::Vector3d(x + 0.5, y + 0.5, 1));
}

using Islands = std::vector<std::vector<int>>;

TEST(Islands, OverlappingBoundsAndContactsLinkStaticBodiesDoNot) {
  // 0: a static floor under everything; 1-2 overlap; 3 alone; 4 touches 5 by contact
  // only (their bounds are apart); 6 overlaps 7, which overlaps 8 (a chain).
  const std::vector<Eigen::AlignedBox3d> bounds = {
      Eigen::AlignedBox3d(Eigen::Vector3d(-50, -50, -1), Eigen::Vector3d(50, 50, 0.1)),
      unitBoxAt(0), unitBoxAt(0.9), unitBoxAt(10), unitBoxAt(20), unitBoxAt(30),
      unitBoxAt(40), unitBoxAt(40.9), unitBoxAt(41.8)};
  const std::vector<char> dynamic = {0, 1, 1, 1, 1, 1, 1, 1, 1};
  const Islands islands = findIslands(bounds, dynamic, {{4, 5}, {0, 3}});
  EXPECT_EQ(islands, (Islands{{1, 2}, {3}, {4, 5}, {6, 7, 8}}));
}

TEST(Islands, BoundsApartAlongYAreNotLinkedThoughTheyOverlapAlongX) {
  const std::vector<Eigen::AlignedBox3d> bounds = {unitBoxAt(0, 0), unitBoxAt(0.2, 5), unitBoxAt(0.4, 0.9)};
  const Islands islands = findIslands(bounds, {1, 1, 1}, {});
  EXPECT_EQ(islands, (Islands{{0, 2}, {1}}));
}

TEST(Islands, OrderDoesNotDependOnWhereTheBodiesAre) {
  // The same links listed in another order and the bodies mirrored along x: the same islands.
  std::vector<Eigen::AlignedBox3d> bounds = {unitBoxAt(5), unitBoxAt(0), unitBoxAt(5.5), unitBoxAt(20)};
  const Islands forward = findIslands(bounds, {1, 1, 1, 1}, {{3, 1}});
  for (Eigen::AlignedBox3d& b : bounds) b = Eigen::AlignedBox3d(-b.max(), -b.min());
  EXPECT_EQ(findIslands(bounds, {1, 1, 1, 1}, {{1, 3}}), forward);
  EXPECT_EQ(forward, (Islands{{0, 2}, {1, 3}}));
}

}  // namespace
}  // namespace polysim::sim
