// findIslands(): which bodies must step through their contact events together, judged by
// their paths relative to each other (islands.h).

#include "sim/islands.h"

#include <gtest/gtest.h>

#include <random>

namespace polysim::sim {
namespace {

constexpr double kT = 0.1;  // s, the step judged

// A unit box at (x, y, 0) moving at `v` (m/s) along x, with `g` (m/s^2) along x along
// its path; its swept box holds every pose over kT.
SweptBody unitBox(double x, double y = 0.0, double v = 0.0, double g = 0.0, bool dynamic = true) {
  SweptBody b;
  b.start = Eigen::AlignedBox3d(Eigen::Vector3d(x - 0.5, y - 0.5, 0), Eigen::Vector3d(x + 0.5, y + 0.5, 1));
  b.velocity = Eigen::Vector3d(v, 0, 0);
  b.gravity = Eigen::Vector3d(g, 0, 0);
  b.dynamic = dynamic;
  const double reach = std::abs(v) * kT + 0.5 * std::abs(g) * kT * kT;
  b.swept = Eigen::AlignedBox3d(b.start.min().array() - reach, b.start.max().array() + reach);
  return b;
}

using Islands = std::vector<std::vector<int>>;

TEST(Islands, OverlappingBoxesAndContactsLinkStaticBodiesDoNot) {
  // 0: a static floor under everything; 1-2 overlap; 3 alone; 4 touches 5 by contact
  // only (they are apart); 6 overlaps 7, which overlaps 8 (a chain).
  SweptBody floor;
  floor.start = floor.swept = Eigen::AlignedBox3d(Eigen::Vector3d(-50, -50, -1), Eigen::Vector3d(50, 50, 0.1));
  const std::vector<SweptBody> bodies = {floor,         unitBox(0),    unitBox(0.9),  unitBox(10),  unitBox(20),
                                         unitBox(30),   unitBox(40),   unitBox(40.9), unitBox(41.8)};
  EXPECT_EQ(findIslands(bodies, kT, {{4, 5}, {0, 3}}, 0.0), (Islands{{1, 2}, {3}, {4, 5}, {6, 7, 8}}));
}

TEST(Islands, BoxesApartAlongYAreNotLinkedThoughTheyOverlapAlongX) {
  const std::vector<SweptBody> bodies = {unitBox(0, 0), unitBox(0.2, 5), unitBox(0.4, 0.9)};
  EXPECT_EQ(findIslands(bodies, kT, {}, 0.0), (Islands{{0, 2}, {1}}));
}

TEST(Islands, BodiesMovingTogetherAreNotLinkedThoughTheirSweptBoxesOverlap) {
  // 0 and 1 fly at 10 m/s with gravity 10 m/s^2, 5 cm apart: they sweep 1.05 m each, and
  // never close the gap. 2 follows 1 at 10.6 m/s, 5 cm behind: it closes 6 cm in kT.
  const std::vector<SweptBody> together = {unitBox(0, 0, 10, 10), unitBox(1.05, 0, 10, 10)};
  ASSERT_TRUE(together[0].swept.intersects(together[1].swept));
  EXPECT_EQ(findIslands(together, kT, {}, 0.0), (Islands{{0}, {1}}));
  const std::vector<SweptBody> closing = {unitBox(0, 0, 10, 10), unitBox(1.05, 0, 10, 10), unitBox(-1.05, 0, 10.6, 10)};
  EXPECT_EQ(findIslands(closing, kT, {}, 0.0), (Islands{{0, 2}, {1}}));
  // A resting box 5 cm ahead of a falling one is reached: gravity does not cancel.
  const std::vector<SweptBody> landing = {unitBox(0, 0, 0, 10), unitBox(1.04, 0, 0, 0)};
  EXPECT_EQ(findIslands(landing, kT, {}, 0.0), (Islands{{0, 1}}));
}

TEST(Islands, OrderDoesNotDependOnWhereTheBodiesAre) {
  // The same links listed in another order and the bodies mirrored along x: the same islands.
  std::vector<SweptBody> bodies = {unitBox(5), unitBox(0), unitBox(5.5), unitBox(20)};
  const Islands forward = findIslands(bodies, kT, {{3, 1}}, 0.0);
  for (SweptBody& b : bodies) {
    b.start = Eigen::AlignedBox3d(-b.start.max(), -b.start.min());
    b.swept = Eigen::AlignedBox3d(-b.swept.max(), -b.swept.min());
  }
  EXPECT_EQ(findIslands(bodies, kT, {{1, 3}}, 0.0), forward);
  EXPECT_EQ(forward, (Islands{{0, 2}, {1, 3}}));
}

// Seeded pairs of boxes on random paths, stepped finely: whenever pathsMayMeet() says
// two are apart, no pose of either over the step comes within the band of the other.
TEST(Islands, PathsJudgedApartStayApartOnSeededPaths) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int apart = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    SweptBody a = unitBox(0), b = unitBox(1.2 + 0.5 * (u(rng) + 1), 0.5 * u(rng));
    a.velocity = 5 * Eigen::Vector3d(u(rng), u(rng), u(rng)), b.velocity = 5 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    a.gravity = Eigen::Vector3d(0, 0, -9.81), b.gravity = u(rng) > 0 ? a.gravity : Eigen::Vector3d::Zero();
    if (!pathsMayMeet(a, b, kT, 0.0)) {
      ++apart;
      for (int k = 0; k <= 100; ++k) {
        const double t = kT * k / 100;
        const SweptBody at = alongPath(a, t, kT), bt = alongPath(b, t, kT);
        EXPECT_GT(at.start.exteriorDistance(bt.start), 0.0) << "trial " << trial << " at " << t << " s";
      }
    }
  }
  EXPECT_GT(apart, 100);  // the test saw paths judged apart
}

}  // namespace
}  // namespace polysim::sim
