// speculativePairs() with `onlyOf` (sim/speculative_contacts.h): testing only the pairs
// of some bodies gives exactly what the whole test gives for those pairs. The step loop
// relies on it after a landing (World::solverContactsOnceLanded), where it keeps the
// other pairs from the test before.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <memory>
#include <random>

#include "collision/shapes.h"
#include "sim/speculative_contacts.h"

namespace polysim::sim {
namespace {

using collision::PairResult;

// A static ground and 4 x 5 x 2 unit boxes, each tilted by up to 0.05 rad about a random
// axis and apart from its neighbours by 0 to 3 cm (the reach is 2 cm): some pairs within
// the reach, some beyond it, some within the tolerance.
collision::ObjectDatabase tiltedBoxes(std::mt19937_64& random) {
  collision::ObjectDatabase db;
  const auto box = std::make_shared<collision::PolygonMesh>(collision::makeBox(Eigen::Vector3d(1, 1, 1)));
  const auto ground = std::make_shared<collision::PolygonMesh>(collision::makeBox(Eigen::Vector3d(20, 20, 1)));
  db.add("ground", ground, Eigen::Isometry3d(Eigen::Translation3d(0, 0, -0.5)), true);
  std::uniform_real_distribution<double> gap(0.0, 0.03), tilt(-0.05, 0.05);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector3d at(i * 1.015 + gap(random), j * 1.015 + gap(random), 0.5 + k * 1.06 + gap(random));
        const Eigen::Vector3d axis = Eigen::Vector3d(tilt(random), tilt(random), tilt(random));
        const Eigen::AngleAxisd turn(axis.norm(), axis.norm() > 0 ? axis.normalized() : Eigen::Vector3d::UnitZ());
        db.add("box", box, Eigen::Translation3d(at) * turn, false);
      }
  return db;
}

void expectSamePair(const PairResult& p, const PairResult& q) {
  EXPECT_EQ(p.a, q.a);
  EXPECT_EQ(p.b, q.b);
  EXPECT_EQ(p.status, q.status);
  ASSERT_EQ(p.contacts.size(), q.contacts.size());
  for (size_t c = 0; c < p.contacts.size(); ++c) {
    EXPECT_EQ(p.contacts[c].normal, q.contacts[c].normal);
    EXPECT_EQ(p.contacts[c].points, q.contacts[c].points);
    EXPECT_EQ(p.contacts[c].gaps, q.contacts[c].gaps);
  }
}

TEST(SpeculativePairs, OnlyTheMarkedBodiesPairsExactlyAsTheWholeTestFindsThem) {
  for (unsigned long long seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 random(seed);
    const collision::ObjectDatabase db = tiltedBoxes(random);
    const int n = static_cast<int>(db.objects.size());
    std::vector<int> bodyOf(n);  // bodies numbered apart from objects, as an island's are
    for (int k = 0; k < n; ++k) bodyOf[k] = 3 * k + 1;
    std::vector<SpeculativeRole> roles(n);
    std::vector<char> marked(3 * n + 1, 0);
    std::uniform_int_distribution<int> pick(0, 5);
    for (int k = 0; k < n; ++k) {
      const int r = pick(random);  // mostly moving; some still, some left; a few marked
      roles[k] = r == 0 ? SpeculativeRole::Left : r == 1 ? SpeculativeRole::Still : SpeculativeRole::Moving;
      marked[bodyOf[k]] = pick(random) == 0;
    }
    const auto roleOf = [&roles](int k) { return roles[k]; };
    collision::IntersectionWorkspace whole, some;
    const std::vector<PairResult> all = speculativePairs(db, whole, kSpeculativeReach, bodyOf, roleOf);
    const std::vector<PairResult> only = speculativePairs(db, some, kSpeculativeReach, bodyOf, roleOf, &marked);
    std::vector<const PairResult*> expected;
    for (const PairResult& p : all)
      if (marked[p.a] || marked[p.b]) expected.push_back(&p);
    ASSERT_GT(all.size(), expected.size()) << "some pairs are not the marked bodies'";
    ASSERT_FALSE(expected.empty()) << "and some are";
    ASSERT_EQ(only.size(), expected.size());
    const auto byPair = [](const PairResult* p, const PairResult* q) { return std::make_pair(p->a, p->b) < std::make_pair(q->a, q->b); };
    std::vector<const PairResult*> got;
    for (const PairResult& p : only) got.push_back(&p);
    std::sort(expected.begin(), expected.end(), byPair);
    std::sort(got.begin(), got.end(), byPair);
    for (size_t i = 0; i < got.size(); ++i) expectSamePair(*got[i], *expected[i]);
  }
}

}  // namespace
}  // namespace polysim::sim
