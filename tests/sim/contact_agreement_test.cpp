// Comparing ODE's contacts with polysim's: distances across the normal to points, lines
// and areas, and the worst disagreement kept with where it happened.

#include "sim/contact_agreement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace polysim::sim {
namespace {

using collision::Contact;
using collision::ContactType;
using V3 = Eigen::Vector3d;

Contact unitSquareOnFloor(double separation = 0.0) {
  Contact c;
  c.type = ContactType::Area;
  c.normal = V3::UnitZ();
  c.points = {V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, 0), V3(0, 1, 0)};
  c.separation = separation;
  return c;
}

dContactGeom odeContact(const V3& p, const V3& n, double depth) {
  dContactGeom g{};
  for (int k = 0; k < 3; ++k) g.pos[k] = p[k], g.normal[k] = n[k];
  g.depth = depth;
  return g;
}

TEST(ContactAgreement, LateralDistanceIgnoresHeightAlongTheNormal) {
  const Contact square = unitSquareOnFloor();
  EXPECT_DOUBLE_EQ(lateralDistanceToContact(square, V3(0.5, 0.5, 0.3)), 0.0);
  EXPECT_DOUBLE_EQ(lateralDistanceToContact(square, V3(1.5, 0.5, -0.2)), 0.5);
  EXPECT_NEAR(lateralDistanceToContact(square, V3(2, 2, 0)), std::sqrt(2.0), 1e-12);

  Contact line;
  line.type = ContactType::Line;
  line.points = {V3(0, 0, 0), V3(1, 0, 0)};
  EXPECT_DOUBLE_EQ(lateralDistanceToContact(line, V3(0.5, 0.25, 1.0)), 0.25);
  EXPECT_DOUBLE_EQ(lateralDistanceToContact(line, V3(-3, 0, 0)), 3.0);

  Contact point;
  point.points = {V3(1, 1, 1)};
  EXPECT_DOUBLE_EQ(lateralDistanceToContact(point, V3(1, 4, 5)), 3.0);
}

TEST(ContactAgreement, MeasuresNormalPointAndDepthAgainstTheNearestContact) {
  collision::PairResult pair;
  pair.contacts = {unitSquareOnFloor(-2e-5)};
  const double press = 2e-4, tolerance = 1e-4;
  const double tilt = 0.01;  // rad
  const std::vector<dContactGeom> ode = {
      odeContact(V3(0, 0, 0), V3::UnitZ(), press + 2e-5),                                  // exact
      odeContact(V3(1.25, 1, 0), V3(std::sin(tilt), 0, std::cos(tilt)), press + 2e-5 + 3e-6),  // off and tilted
  };
  const PairDisagreement d = comparePairContacts(pair, ode, press, tolerance);
  EXPECT_EQ(d.odeContacts, 2);
  EXPECT_NEAR(d.normalAngle, tilt, 1e-12);
  EXPECT_NEAR(d.pointDistance, 0.25, 1e-12);
  EXPECT_NEAR(d.depthError, 3e-6, 1e-12);
}

// A normal pointing the other way (from a to b) is the worst disagreement there is,
// half a turn, not agreement.
TEST(ContactAgreement, AFlippedNormalIsHalfATurnOff) {
  collision::PairResult pair;
  pair.contacts = {unitSquareOnFloor()};
  const std::vector<dContactGeom> ode = {odeContact(V3(0.5, 0.5, 0), -V3::UnitZ(), 2e-4)};
  EXPECT_NEAR(comparePairContacts(pair, ode, 2e-4, 1e-4).normalAngle, M_PI, 1e-12);
}

TEST(ContactAgreement, LeavesOutOdeContactsThatPressingBroughtInFromBeyondTheTolerance) {
  collision::PairResult pair;
  pair.contacts = {unitSquareOnFloor()};
  const double press = 2e-4, tolerance = 1e-4;
  // A far corner 1.5 tolerances away before pressing: ODE sees it 0.5 tolerances deep.
  const PairDisagreement d = comparePairContacts(pair, {odeContact(V3(5, 5, 0), V3::UnitZ(), 0.5e-4)}, press, tolerance);
  EXPECT_EQ(d.odeContacts, 0);
  EXPECT_EQ(d.pointDistance, 0.0);
}

TEST(ContactAgreement, KeepsTheWorstOfEachMeasureWithItsTimeAndPair) {
  ContactAgreement agreement;
  collision::PairResult pair;
  pair.contacts = {unitSquareOnFloor()};
  agreement.add(0.1, "a", "ground", pair, {}, {1, 0.02, 0.0, 1e-6});
  agreement.add(0.2, "b", "ground", pair, {}, {1, 0.01, 0.3, 1e-7});
  agreement.add(0.3, "c", "ground", pair, {}, {0, 0.0, 0.0, 0.0});  // ODE saw nothing
  EXPECT_EQ(agreement.pairsCompared(), 3);
  EXPECT_EQ(agreement.pairsOdeMissed(), 1);
  const nlohmann::ordered_json j = agreement.toJson();
  EXPECT_EQ(j["normal_angle_rad"]["pair"], "a/ground");
  EXPECT_DOUBLE_EQ(j["normal_angle_rad"]["time"].get<double>(), 0.1);
  EXPECT_EQ(j["point_distance"]["pair"], "b/ground");
  EXPECT_DOUBLE_EQ(j["point_distance"]["max"].get<double>(), 0.3);
  EXPECT_EQ(j["depth_error"]["pair"], "a/ground");
  EXPECT_EQ(j["ode_missed"]["first_pair"], "c/ground");
  EXPECT_EQ(j["point_distance"]["polysim"].size(), 1u);
}

TEST(ContactAgreement, PressDirectionIsTheMeanNormal) {
  collision::PairResult pair;
  Contact a = unitSquareOnFloor(), b = unitSquareOnFloor();
  b.normal = V3::UnitX();
  pair.contacts = {a, b};
  EXPECT_TRUE(pressDirection(pair).isApprox(V3(1, 0, 1).normalized()));
}

}  // namespace
}  // namespace polysim::sim
