// The contacts a step reports (World::contacts()) are the whole database's: the world
// steps its bodies in islands (islands.h), reuses contacts (contact_reuse.h) and speculates
// (speculative_contacts.h), yet no pair within the tolerance may be missing at a step's
// end, nor a pair reported that a fresh test of all objects finds apart.

#include <gtest/gtest.h>

#include <set>

#include "tests/sim/scenario_support.h"

namespace polysim::sim {
namespace {

using test::V3;
using Pairs = std::set<std::pair<int, int>>;

// The pairs a fresh test4Intersection() of the world's current poses finds within
// `tolerance` (m): no contact reuse and nothing kept from the world's own tests.
Pairs freshPairsWithin(const World& w, double tolerance) {
  collision::ObjectDatabase db = buildObjectDatabase(w.scene());
  db.tolerance = tolerance;
  for (size_t i = 0; i < db.objects.size(); ++i) db.objects[i].X_WO = w.bodies()[i].pose();
  Pairs pairs;
  for (const collision::PairResult& p : collision::test4Intersection(db).pairs) pairs.insert(bodyPair(p.a, p.b));
  return pairs;
}

Pairs reportedPairs(const World& w) {
  Pairs pairs;
  for (const collision::PairResult& p : w.contacts())
    if (p.status != collision::Status::Separate) pairs.insert(bodyPair(p.a, p.b));
  return pairs;
}

// After every step for `seconds`: each pair a fresh test finds within half the tolerance
// is reported, and each pair reported is within twice the tolerance. The slack keeps the
// check off the tolerance's edge, where a carried-over contact may stand a hair beyond it.
// Returns the islands joined over the run (StepReport::islandsJoined).
int expectContactsOfTheWholeDatabase(World& w, double seconds) {
  const double tolerance = w.scene().contact.tolerance;
  int checked = 0, redone = 0;
  test::runFor(w, seconds, [&](const StepReport& r) {
    redone += r.islandsJoined;
    const Pairs reported = reportedPairs(w);
    checked += static_cast<int>(reported.size());
    if (testing::Test::HasFailure()) return;  // one step's report is enough
    for (const auto& p : freshPairsWithin(w, tolerance / 2))
      EXPECT_TRUE(reported.count(p)) << "step " << r.step << ": bodies " << p.first << " and " << p.second
                                     << " are within half the tolerance but not among the step's contacts";
    const Pairs near = freshPairsWithin(w, 2 * tolerance);
    for (const auto& p : reported)
      EXPECT_TRUE(near.count(p)) << "step " << r.step << ": bodies " << p.first << " and " << p.second
                                 << " are reported in contact but are farther apart than twice the tolerance";
  });
  EXPECT_GT(checked, 0) << "no contacts at all: the scene tests nothing";
  return redone;
}

// Seeded rows of boxes of random sizes resting on the floor along x, each a random gap
// from the last: within the tolerance for some neighbours (a contact no motion brings
// about: the world must know it from the start), beyond it for others. Nothing moves,
// so no island is ever stepped again.
TEST(StepContacts, RestingRowsReportEveryNeighbourWithinTheTolerance) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    ::polysim::test::SeededDraws draw(seed);
    Scene scene = test::scene("box_on_ground", false);
    scene.dt = 1.0 / 60;
    const BodySpec boxTemplate = scene.bodies[1];
    scene.bodies.resize(1);
    const double tolerance = scene.contact.tolerance;
    double x = 0.0;
    const int count = 3 + static_cast<int>(seed % 5);
    for (int k = 0; k < count; ++k) {
      BodySpec box = boxTemplate;
      box.name = "box" + std::to_string(k);
      test::setBoxSize(box, draw.vector(0.3, 1.0));
      box.mass = draw.between(0.5, 3.0);
      if (k > 0) x += draw.between(0.0, 2.0) * tolerance;  // the gap: half the rows' gaps are within the tolerance
      box.position = V3(x + box.boxSize.x() / 2, 0, box.boxSize.z() / 2);
      x += box.boxSize.x();
      scene.bodies.push_back(box);
    }
    World w(scene);
    EXPECT_EQ(expectContactsOfTheWholeDatabase(w, 0.5), 0) << "islands redone, though nothing moves";
  }
}

// A box creeps along a frictionless floor at 0.5 to 3 mm/s toward a resting box a few
// millimetres away. It moves less in a step than the tolerance, so for several steps
// before they meet the two are within the tolerance while their bounds, grown by the
// creeper's motion alone, are still apart: only bounds grown by the tolerance too put
// them in one island at once, whose test finds them in contact.
TEST(StepContacts, ABoxCreepingUpToAnotherIsInContactFromWithinTheTolerance) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    ::polysim::test::SeededDraws draw(seed);
    Scene scene = test::scene("box_on_ground", false);
    scene.dt = 1.0 / 60;
    scene.contact.friction = 0.0;
    BodySpec creeper = scene.bodies[1];
    test::setBoxSize(creeper, draw.vector(0.3, 1.0));
    creeper.position = V3(0, 0, creeper.boxSize.z() / 2);
    const double speed = draw.between(0.5e-3, 3e-3), gap = draw.between(1e-3, 3e-3);
    creeper.velocity = V3(speed, 0, 0);
    BodySpec resting = creeper;
    resting.name = "resting";
    test::setBoxSize(resting, draw.vector(0.3, 1.0));
    resting.velocity.setZero();
    const double sideways = draw.between(-0.1, 0.1);
    resting.position = V3((creeper.boxSize.x() + resting.boxSize.x()) / 2 + gap, sideways, resting.boxSize.z() / 2);
    scene.bodies[1] = creeper;
    scene.bodies.push_back(resting);
    World w(scene);
    // No impulse speeds a body up before they meet, and from then on they share an island,
    // so no island outgrows its bounds. Bounds not grown by the tolerance would be
    // outgrown (World::outgrewItsBounds) as the two come within it, and stepped again.
    EXPECT_EQ(expectContactsOfTheWholeDatabase(w, gap / speed + 0.5), 0) << "islands redone";
    EXPECT_TRUE(reportedPairs(w).count({1, 2})) << "the creeper ends touching the box it pushes";
  }
}

// The same on busy scenes: seeded tilted piles landing and settling, where islands merge
// and split, contacts are carried over and bodies land every step.
TEST(StepContacts, TiltedPilesReportTheWholeDatabasesContacts) {
  for (unsigned long long seed : {2ull, 5ull}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    World w(test::generated("pile", 27, seed, 0.3));
    expectContactsOfTheWholeDatabase(w, 2.0);
  }
}

}  // namespace
}  // namespace polysim::sim
