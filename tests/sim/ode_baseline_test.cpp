// The ODE baseline: the same scenes in ODE agree with polysim where both are right, the
// contact comparison sees the same contacts, and what ODE cannot model is refused.

#include "sim/ode_baseline.h"

#include <gtest/gtest.h>

#include <cmath>

namespace polysim::sim {
namespace {

Scene scene(const std::string& name) { return loadScene(std::string(POLYSIM_SCENES_DIR) + "/" + name + ".json"); }

double z(const nlohmann::ordered_json& body) { return body["position"][2].get<double>(); }

TEST(OdeBaseline, DropBoxRestsAtHalfItsHeightInBothEnginesWithTheSameContacts) {
  const Scene drop = scene("drop_box");
  const nlohmann::ordered_json c = compareWithOde(drop, {});
  EXPECT_NEAR(z(c["polysim"]["bodies"][0]), 0.5, 1e-3);
  EXPECT_NEAR(z(c["ode"]["bodies"][0]), 0.5, 1e-3);
  EXPECT_TRUE(c["ode"]["bodies"][0]["at_rest"].get<bool>());
  // Both first touch within a step of each other, near the analytic sqrt(2 * 1.5 / 9.81).
  const double analytic = std::sqrt(2 * 1.5 / 9.81);
  EXPECT_NEAR(c["comparison"]["first_contact_time"][0].get<double>(), analytic, drop.dt);
  EXPECT_NEAR(c["comparison"]["first_contact_time"][1].get<double>(), analytic, drop.dt);

  // Every resting state was handed to ODE, which saw the same face contact: the same
  // normal, its points on polysim's square, its depth the press less polysim's separation.
  const auto& contacts = c["comparison"]["contacts"];
  EXPECT_GT(contacts["pairs"].get<long>(), 500);
  EXPECT_EQ(contacts["ode_missed"]["count"], 0);
  EXPECT_LT(contacts["normal_angle_rad"]["max"].get<double>(), 1e-6);
  EXPECT_LT(contacts["point_distance"]["max"].get<double>(), 1e-6);
  EXPECT_LT(contacts["depth_error"]["max"].get<double>(), drop.contact.tolerance);
  EXPECT_EQ(contacts["depth_error"]["pair"], "box/ground");
}

TEST(OdeBaseline, StackOfFiveStandsInBothEngines) {
  RunOptions shorter;
  shorter.duration = 10.0;
  const nlohmann::ordered_json c = compareWithOde(scene("stack_5"), shorter);
  for (const char* engine : {"polysim", "ode"})
    for (size_t k = 0; k < 5; ++k) EXPECT_NEAR(z(c[engine]["bodies"][k]), 0.5 + k, 1e-2) << engine << " box" << k;
  for (const auto& body : c["comparison"]["bodies"]) {
    EXPECT_LT(body["drift"][0].get<double>(), 1e-3) << body["name"];
    EXPECT_LT(body["drift"][1].get<double>(), 5e-2) << body["name"];
  }
  EXPECT_EQ(c["comparison"]["contacts"]["pairs"].get<long>(), 5 * 600);  // 5 touching pairs in each of 600 steps
}

// QuickStep shuffles its rows with ODE's global random generator; a run must not depend
// on the runs before it in the process (the serial sweep and a planned run disagreed).
TEST(OdeBaseline, QuickStepRunsAreTheSameWhateverRanBefore) {
  RunOptions shorter;
  shorter.duration = 2.0;
  const nlohmann::ordered_json first = runOde(scene("stack_5"), shorter);
  runOde(scene("bounce"), shorter);
  const nlohmann::ordered_json again = runOde(scene("stack_5"), shorter);
  EXPECT_EQ(first["bodies"].dump(), again["bodies"].dump());
  EXPECT_EQ(first["max_penetration"], again["max_penetration"]);
}

// ODE's known failure, shown as what it is: boxes given as triangle meshes resting on
// each other. ODE's trimesh-trimesh contacts let them sink into one another; polysim's
// stack of the same polygons stands.
TEST(OdeBaseline, TriangleMeshBoxesOnEachOtherAreAKnownOdeFailure) {
  const nlohmann::ordered_json c = compareWithOde(scene("stack_5_meshes"), {});
  const auto& bodies = c["comparison"]["bodies"];
  for (size_t k = 0; k < 5; ++k) EXPECT_NEAR(bodies[k]["height_change"][0].get<double>(), 0.0, 1e-3) << "polysim box" << k;
  EXPECT_LT(bodies[4]["height_change"][1].get<double>(), -0.5) << "ODE's top box sank";
  EXPECT_GT(c["ode"]["max_penetration"].get<double>(), 0.1);
  bool reported = false;
  for (const auto& f : c["comparison"]["findings"])
    reported = reported || f.get<std::string>().rfind("ode: contacts overlapped by up to", 0) == 0;
  EXPECT_TRUE(reported) << c["comparison"]["findings"].dump();
  // At polysim's poses ODE's trimesh contacts disagree too: normals turned by up to 90 degrees.
  EXPECT_GT(c["comparison"]["contacts"]["normal_angle_rad"]["max"].get<double>(), 0.5);
}

TEST(OdeBaseline, RampSlideAgreesWithPolysim) {
  const nlohmann::ordered_json c = compareWithOde(scene("ramp_slides"), {});
  EXPECT_LT(c["comparison"]["bodies"][0]["position_difference"].get<double>(), 1e-3);
  EXPECT_LT(c["comparison"]["contacts"]["normal_angle_rad"]["max"].get<double>(), 1e-3);
}

TEST(OdeBaseline, FindingsNameABodyThatLeftEveryStaticBodyBehind) {
  RunOptions longer;
  longer.duration = 4.0;  // the box slides off the 8 m ramp and falls below it
  const nlohmann::ordered_json c = compareWithOde(scene("ramp_slides"), longer);
  int fellOff = 0;
  for (const auto& f : c["comparison"]["findings"])
    fellOff += f.get<std::string>().find("box ended at height") != std::string::npos;
  EXPECT_EQ(fellOff, 2);  // in both engines
}

// ODE's summary of the bounce scene (1 kg unit box, centre 1.5 m up, e 0.5, dt 1 ms,
// 1.5 s) against figures worked by hand: SPEC's fields mean the same in both engines.
TEST(OdeBaseline, SummaryOfTheBounceHasSpecFiguresWorkedByHand) {
  const Scene bounce = scene("bounce");
  const nlohmann::ordered_json s = runOde(bounce, {});
  EXPECT_EQ(s["scene"], "bounce");
  EXPECT_EQ(s["steps"].get<long>(), 1500);
  EXPECT_NEAR(s["sim_time"].get<double>(), 1.5, 1e-12);
  EXPECT_GE(s["wall_time_s"].get<double>(), 0.0);
  // Energy: m g z of the centre at rest in free fall, then what the bounce leaves.
  EXPECT_NEAR(s["energy"]["initial"].get<double>(), 1.0 * 9.81 * 1.5, 1e-9);
  EXPECT_LT(s["energy"]["final"].get<double>(), s["energy"]["initial"].get<double>());
  EXPECT_GE(s["energy"]["max_increase"].get<double>(), 0.0);
  // First contact at the first step end after sqrt(2h/g) (h = 1 m): ODE sees overlaps only.
  const double fall = std::sqrt(2 * 1.0 / 9.81);
  EXPECT_GE(s["first_contact_time"].get<double>(), fall - 1e-12);
  EXPECT_LE(s["first_contact_time"].get<double>(), fall + 2 * bounce.dt);
  EXPECT_GT(s["max_penetration"].get<double>(), 0.0);  // ODE lets the box overlap at impact
  EXPECT_LT(s["max_penetration"].get<double>(), 0.05);
  ASSERT_EQ(s["bodies"].size(), 1u);
  EXPECT_EQ(s["bodies"][0]["name"], "box");
  EXPECT_NEAR(z(s["bodies"][0]), 0.5, 0.02);  // settled or nearly so on the ground by 1.5 s
  EXPECT_EQ(s["settings"]["stepper"], "quickstep");
  EXPECT_EQ(s["settings"]["iterations"], 20);
}

TEST(OdeBaseline, TheLinkedOdeIsDoublePrecisionWithTriangleMeshes) {
  const OdeCapabilities ode = OdeCapabilities::ofLinkedLibrary();
  EXPECT_TRUE(ode.doublePrecision);
  EXPECT_TRUE(ode.triMesh);
  EXPECT_NO_THROW(checkOdeCanModel(scene("cup_catch"), ode));
}

TEST(OdeBaseline, RefusesMeshesWhenOdeHasNoTriangleMeshCollider) {
  OdeCapabilities boxesOnly;
  boxesOnly.triMesh = false;
  EXPECT_NO_THROW(checkOdeCanModel(scene("drop_box"), boxesOnly));
  try {
    checkOdeCanModel(scene("cup_catch"), boxesOnly);
    FAIL() << "the cup is a mesh";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cup_catch.json"), std::string::npos) << message;
    EXPECT_NE(message.find("body \"cup\": shape"), std::string::npos) << message;
    EXPECT_NE(message.find("triangle-mesh collider"), std::string::npos) << message;
    EXPECT_EQ(message.find("\"box\""), std::string::npos) << "boxes are dBox: " << message;
  }
}

TEST(OdeBaseline, RefusesMeshesBeyondSixteenBitIndicesAndSinglePrecision) {
  OdeCapabilities small;
  small.maxTriMeshVertices = 8;  // the cup has 16 vertices
  EXPECT_THROW(checkOdeCanModel(scene("cup_catch"), small), SceneError);
  OdeCapabilities single;
  single.doublePrecision = false;
  EXPECT_THROW(checkOdeCanModel(scene("drop_box"), single), SceneError);
}

}  // namespace
}  // namespace polysim::sim
