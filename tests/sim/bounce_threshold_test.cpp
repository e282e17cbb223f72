// The bounce threshold: an impact faster than kBounceThreshold rebounds at e times its
// speed; a slower one does not rebound at all, so the box stops on it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dynamics/settings.h"
#include "sim/scene.h"
#include "sim/world.h"
#include "tests/sim/scenario_support.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

using namespace polysim::sim::test;

// A box of seeded size, mass and yaw dropped flat from rest onto the ground, with a
// seeded restitution e. Impact k comes at v0 e^k. The drop height is chosen so that
// impact n is the first slower than the threshold, by a margin: v0 e^n = threshold
// sqrt(e), so impact n-1 is at threshold / sqrt(e). Each flight k (after impact k-1) then
// rises to (v0 e^k)^2 / 2g, and after impact n the box stays on the ground.
TEST(BounceThreshold, ImpactsBelowTheThresholdDoNotReboundOnSeededDrops) {
  const double threshold = dynamics::kBounceThreshold;
  for (unsigned long long seed = 1; seed <= 6; ++seed) {
    ::polysim::test::SeededDraws draw(seed);
    const double e = draw.between(0.4, 0.85);
    const int n = 1 + static_cast<int>(draw.between(0.0, 3.0));  // rebounds: 1 to 3
    const double dt = draw.between(0.0, 1.0) < 0.5 ? 1.0 / 120.0 : 1.0 / 240.0;
    const V3 size = draw.vector(0.3, 1.5);
    const double mass = draw.between(0.5, 20.0), yaw = draw.between(-3.0, 3.0);
    const double v0 = threshold * std::sqrt(e) / std::pow(e, n);
    SCOPED_TRACE(testing::Message() << "seed " << seed << ": e " << e << ", " << n << " rebounds, v0 " << v0);

    Scene s = scene("bounce_e09", false);
    s.dt = dt;
    s.contact.restitution = e;
    BodySpec& box = s.bodies[1];
    setBoxSize(box, size);
    box.mass = mass;
    box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, V3::UnitZ()));
    box.position = V3(0.3, -0.2, size.z() / 2 + v0 * v0 / (2 * g));
    World w(s);
    const double tol = w.scene().contact.tolerance;

    // The highest gap of each flight after a rebound: a step that ends rising after one
    // that did not. Every rebound leaves at over 0.12 m/s (one at impact n, were it kept,
    // at e^1.5 threshold, the slowest); a box at rest moves at round-off.
    const double rising = 0.05;  // m/s
    std::vector<double> apexes;
    double lastVz = 0;  // m/s
    runFor(w, 1.0 + v0 / g * (1 + 2 * e / (1 - e)), [&](const StepReport&) {
      const double gap = w.bodies()[1].position.z() - size.z() / 2, vz = w.bodies()[1].velocity.z();
      if (vz > rising && lastVz <= rising) apexes.push_back(gap);
      if (!apexes.empty()) apexes.back() = std::max(apexes.back(), gap);
      lastVz = vz;
    });

    ASSERT_EQ(static_cast<int>(apexes.size()), n) << "rebounds";
    // Below the flight's analytic apex by up to g dt^2 / 8, as a step's end falls within
    // dt/2 of the apex, and by up to g dt^2 / 2 more when the rebound came at a step's
    // start (a step that ended within the band): a body in contact moves over its step at
    // the step's end velocity, after gravity.
    for (int k = 1; k <= n; ++k) {
      const double speed = v0 * std::pow(e, k), apex = speed * speed / (2 * g);
      EXPECT_LE(apexes[k - 1], apex + 2 * tol) << "flight " << k;
      EXPECT_GE(apexes[k - 1], apex - 5 * g * dt * dt / 8 - 2 * tol) << "flight " << k;
    }
    EXPECT_LT(w.bodies()[1].velocity.norm(), 1e-6);
    EXPECT_LE(w.bodies()[1].position.z() - size.z() / 2, tol);
  }
}

}  // namespace
}  // namespace polysim::sim
