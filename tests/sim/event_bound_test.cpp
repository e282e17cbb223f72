// The bound on contact events in a step (kMaxEventsPerStep) is per body: it stops a box
// bouncing ever lower, not an island in which many bodies each land once.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "sim/world.h"
#include "tests/sim/scenario_support.h"

namespace polysim::sim {
namespace {

using test::g;

// A row of 12 unit boxes resting side by side on the floor, each sunk half a tolerance
// into its neighbour (one island, by their contacts), and a box of 0.8 m above each (not
// touching its neighbours, so flying free: a body in contact would meet the row through
// speculative contacts, with no event), its bottom d_k = 0.27 m + k mm above the row:
// they land at sqrt(2 d_k / g), 0.44 ms apart, all within one step of 1/60 s and all in
// the row's island. Each landing is its own event at its own time; no step reaches the
// bound (an island's bound of 8 would stop the island's clock at the eighth, and the
// last boxes would land a step late).
TEST(EventBound, TwelveBoxesLandingOnOneIslandInOneStepEachLandOnTime) {
  constexpr int kRow = 12;
  constexpr double eps = 1e-4;
  std::string bodies = R"({"name": "floor", "static": true, "shape": {"type": "box", "size": [40, 10, 1]}, "position": [0, 0, -0.5]})";
  for (int k = 0; k < kRow; ++k) {
    const double x = k * (1.0 - 0.5 * eps);
    bodies += R"(, {"name": "row)" + std::to_string(k) + R"(", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [)" +
              std::to_string(x) + ", 0, 0.5]}";
    const double drop = 0.27 + 1e-3 * k;
    bodies += R"(, {"name": "drop)" + std::to_string(k) + R"(", "shape": {"type": "box", "size": [0.8, 0.8, 0.8]}, "position": [)" +
              std::to_string(x) + ", 0, " + std::to_string(1.4 + drop) + "]}";
  }
  const std::string path = ::polysim::test::tempPath("event_bound_row.json");
  std::ofstream(path) << R"({"dt": 0.016666666666666666, "duration": 0.5, "contact": {"tolerance": 0.0001},)"
                      << R"( "sleep": {"enabled": false}, "bodies": [)" << bodies << "]}\n";
  World w(loadScene(path));
  std::vector<double> landing(w.bodies().size(), -1.0);
  int mostIslandEvents = 0;
  while (w.time() < 0.5 - 1e-9) {
    const StepReport& r = w.step(w.scene().dt);
    EXPECT_FALSE(r.eventLimitHit) << "step " << r.step;
    for (const IslandReport& island : r.islands) mostIslandEvents = std::max(mostIslandEvents, island.events);
    for (const StepEvent& e : r.events)
      for (const auto& [a, b] : e.toc.crossing)
        for (int i : {a, b})
          if (landing[i] < 0.0) landing[i] = e.time;
  }
  EXPECT_GE(mostIslandEvents, kRow);
  for (int k = 0; k < kRow; ++k) {
    const int drop = test::bodyIndex(w, "drop" + std::to_string(k));
    const double d = 0.27 + 1e-3 * k;
    const double speed = std::sqrt(2 * g * d);
    SCOPED_TRACE("drop" + std::to_string(k));
    // Just contact: the gap within the band, so the time within 2 eps over the speed.
    EXPECT_NEAR(landing[drop], std::sqrt(2 * d / g), 2 * eps / speed);
  }
}

}  // namespace
}  // namespace polysim::sim
