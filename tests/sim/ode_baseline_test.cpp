// The ODE baseline: the same scenes in ODE agree with polysim where both are right.

#include "sim/ode_baseline.h"

#include <gtest/gtest.h>

namespace polysim::sim {
namespace {

Scene scene(const std::string& name) { return loadScene(std::string(POLYSIM_SCENES_DIR) + "/" + name + ".json"); }

double z(const nlohmann::ordered_json& body) { return body["position"][2].get<double>(); }

TEST(OdeBaseline, DropBoxRestsAtHalfItsHeightInBothEngines) {
  const nlohmann::ordered_json c = compareWithOde(scene("drop_box"), {});
  EXPECT_NEAR(z(c["polysim"]["bodies"][0]), 0.5, 1e-3);
  EXPECT_NEAR(z(c["ode"]["bodies"][0]), 0.5, 1e-3);
  EXPECT_TRUE(c["ode"]["bodies"][0]["at_rest"].get<bool>());
  // Both first touch within a step of each other.
  EXPECT_NEAR(c["comparison"]["first_contact_time"][0].get<double>(), c["comparison"]["first_contact_time"][1].get<double>(),
              scene("drop_box").dt);
}

TEST(OdeBaseline, StackOfFiveStandsInBothEngines) {
  RunOptions shorter;
  shorter.duration = 10.0;
  const nlohmann::ordered_json c = compareWithOde(scene("stack_5"), shorter);
  for (const char* engine : {"polysim", "ode"})
    for (size_t k = 0; k < 5; ++k) EXPECT_NEAR(z(c[engine]["bodies"][k]), 0.5 + k, 1e-2) << engine << " box" << k;
}

TEST(OdeBaseline, RampSlideAgreesWithPolysim) {
  const nlohmann::ordered_json c = compareWithOde(scene("ramp_slides"), {});
  EXPECT_LT(c["comparison"]["bodies"][0]["position_difference"].get<double>(), 1e-3);
}

TEST(OdeBaseline, SummaryHasSpecFieldsAndTheSettingsUsed) {
  const nlohmann::ordered_json s = runOde(scene("bounce"), {});
  for (const char* key : {"scene", "steps", "sim_time", "wall_time_s", "first_contact_time", "max_penetration", "energy", "bodies"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(s["settings"]["stepper"], "quickstep");
  EXPECT_EQ(s["settings"]["iterations"], 20);
}

}  // namespace
}  // namespace polysim::sim
