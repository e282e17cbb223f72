// Contact reuse in the step loop (collision/contact_reuse.h): a resting structure keeps its
// contacts from step to step and ends where it ends when every pair is tested afresh;
// a settling pile, whose pairs mostly move too much to be reused, keeps its invariants.

#include <gtest/gtest.h>

#include <string>

#include "tests/sim/scenario_support.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

Scene generated(const std::string& kind, int count, unsigned long long seed, bool reuse) {
  Scene scene = test::generated(kind, count, seed);  // sleeping off: every pair is tested every step
  scene.contact.reuseContacts = reuse;
  return scene;
}

double energyBound(const World& w) {
  double bound = 0.0;
  for (const dynamics::RigidBody& b : w.bodies()) bound += b.mass * w.scene().gravity.norm() * w.scene().contact.tolerance;
  return bound;
}

// A pyramid with a base of 6 (21 boxes) standing for 2 s: with reuse, its pairs are
// tested once and reused ever after, and every box ends within 1e-9 m of where it ends
// when each pair is tested every time.
TEST(ContactReuse, ARestingPyramidEndsAsWhenEveryPairIsTested) {
  World reusing(generated("pyramid", 6, 1, true));
  World testing(generated("pyramid", 6, 1, false));
  long pairSteps = 0;
  test::runFor(reusing, 2.0, [&](const StepReport&) { pairSteps += static_cast<long>(reusing.contacts().size()); });
  test::runFor(testing, 2.0, [](const StepReport&) {});
  EXPECT_EQ(testing.contactsReused(), 0);
  EXPECT_GT(reusing.contactsReused(), pairSteps / 2) << "of " << pairSteps << " pairs in contact at steps' ends";
  double largest = 0.0;
  for (size_t i = 0; i < reusing.bodies().size(); ++i)
    largest = std::max(largest, (reusing.bodies()[i].position - testing.bodies()[i].position).norm());
  EXPECT_LT(largest, 1e-9);
  for (size_t i = 0; i < reusing.bodies().size(); ++i) EXPECT_TRUE(reusing.atRest(static_cast<int>(i)));
}

// Seeded piles of 27 tilted boxes and columns of 6 cups (not convex): landing, toppling
// and settling with reuse on. The energy bound holds, nothing overlaps deeper than the
// tolerance by the contacts nor interpenetrates by a fresh test, nothing is NaN; once
// settled, the boxes' pairs are reused. The cups' are not: a pair judged by its polygons'
// depth is never kept (contact_reuse.h).
TEST(ContactReuse, SettlingPilesAndCupsKeepTheirInvariants) {
  for (const auto& [kind, count, seconds] : {std::tuple{"pile", 27, 5.0}, std::tuple{"cups", 6, 5.0}}) {
    for (unsigned long long seed : {5ull, 6ull}) {
      SCOPED_TRACE(std::string(kind) + ", seed " + std::to_string(seed));
      World w(generated(kind, count, seed, true));
      const double initial = w.energy();
      double rise = 0.0, deepest = 0.0;
      bool finite = true;
      int interpenetrating = 0;
      test::FreshVerdict fresh(w.scene());
      test::runFor(w, seconds, [&](const StepReport& r) {
        rise = std::max(rise, w.energy() - initial);
        deepest = std::max(deepest, r.penetration);
        interpenetrating += fresh.interpenetrating(w);
        for (const dynamics::RigidBody& b : w.bodies()) finite = finite && b.position.allFinite() && b.velocity.allFinite();
      });
      EXPECT_TRUE(finite);
      EXPECT_LE(rise, energyBound(w));
      EXPECT_LE(deepest, w.scene().contact.tolerance);
      EXPECT_EQ(interpenetrating, 0) << "steps ending interpenetrating by a fresh test";
      if (std::string(kind) == "pile") {
        EXPECT_GT(w.contactsReused(), 0);
      } else {
        EXPECT_EQ(w.contactsReused(), 0);
      }
    }
  }
}

}  // namespace
}  // namespace polysim::sim
