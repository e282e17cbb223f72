// EventReach (sim/event_reach.h): which groups of contacts an event's solve covers. A
// group is linked through dynamic bodies; the ground links nothing.

#include "sim/event_reach.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace polysim::sim {
namespace {

using collision::PairResult;

dynamics::RigidBody unitBox() {
  dynamics::MassProperties props;
  props.mass = 1.0;
  props.inertia = Eigen::Matrix3d::Identity() / 6.0;
  return dynamics::RigidBody::dynamic(props);
}

PairResult pair(int a, int b, int contacts = 1) {
  PairResult p;
  p.a = a, p.b = b;
  p.status = collision::Status::Contact;
  p.contacts.resize(static_cast<size_t>(contacts));
  return p;
}

std::vector<std::pair<int, int>> pairsOf(const std::vector<PairResult>& pairs) {
  std::vector<std::pair<int, int>> out;
  for (const PairResult& p : pairs) out.emplace_back(p.a, p.b);
  return out;
}

// Ground 0; two columns, 1 on 2 on the ground and 3 on 4 on the ground, each solved at
// the step's start. Bodies move fast (1 m/s), so no group is settling.
struct EventReachOfTwoColumns : ::testing::Test {
  void SetUp() override {
    bodies.push_back(dynamics::RigidBody::fixed());
    for (int i = 1; i <= 5; ++i) bodies.push_back(unitBox()), bodies.back().velocity = Eigen::Vector3d(1.0, 0.0, 0.0);
    sizes.assign(bodies.size(), 0.87);
    reach.newStep();
    reach.noteSolved(contacts, bodies);
  }
  std::vector<dynamics::RigidBody> bodies;
  std::vector<double> sizes;
  std::vector<PairResult> contacts{pair(0, 2, 4), pair(1, 2, 4), pair(0, 4, 4), pair(3, 4, 4)};
  EventReach reach{6};
  const std::vector<std::pair<int, int>> left{{0, 2}, {1, 2}}, right{{0, 4}, {3, 4}};
};

TEST_F(EventReachOfTwoColumns, AnEventCoversItsCrossingPairsGroupOnly) {
  EXPECT_EQ(pairsOf(reach.reached(contacts, {{3, 4}}, bodies, sizes)), right);
  EXPECT_EQ(pairsOf(reach.reached(contacts, {{0, 2}}, bodies, sizes)), left);
  EXPECT_TRUE(reach.reached(contacts, {}, bodies, sizes).empty());
}

TEST_F(EventReachOfTwoColumns, AVelocityChangedSinceItsSolveBringsItsGroup) {
  bodies[1].angularVelocity.z() += 1e-15;  // gravity given on landing, say: any bit counts
  EXPECT_EQ(pairsOf(reach.reached(contacts, {}, bodies, sizes)), left);
}

TEST_F(EventReachOfTwoColumns, APairNewToTheBandOrWithOtherContactsBringsItsGroup) {
  std::vector<PairResult> now = contacts;
  now[3] = pair(3, 4, 2);  // the face contact became a line
  EXPECT_EQ(pairsOf(reach.reached(now, {}, bodies, sizes)), right);
  now = contacts;
  now.push_back(pair(0, 5));  // body 5 lands, its pair never solved
  EXPECT_EQ(pairsOf(reach.reached(now, {}, bodies, sizes)), (std::vector<std::pair<int, int>>{{0, 5}}));
}

TEST_F(EventReachOfTwoColumns, AContactLinkingTheColumnsJoinsTheirGroups) {
  std::vector<PairResult> now = contacts;
  now.push_back(pair(1, 3));  // the top boxes touch: one group, which the event reaches
  EXPECT_EQ(reach.reached(now, {{0, 2}}, bodies, sizes).size(), now.size());
}

TEST_F(EventReachOfTwoColumns, ANewStepForgetsEverySolve) {
  reach.newStep();
  EXPECT_EQ(reach.reached(contacts, {}, bodies, sizes).size(), contacts.size());
}

TEST_F(EventReachOfTwoColumns, ASettlingGroupIsSweptAgainAndARestingOrFastOneIsNot) {
  for (int i : {3, 4}) bodies[i].velocity = Eigen::Vector3d(0.0, 0.0, 1e-3);
  reach.noteSolved(contacts, bodies);  // as its last solve left it, slower than kSettlingSpeed
  EXPECT_EQ(pairsOf(reach.reached(contacts, {}, bodies, sizes)), right);
  for (int i : {3, 4}) bodies[i].restedAfterLastSolve = true;
  EXPECT_TRUE(reach.reached(contacts, {}, bodies, sizes).empty());
  bodies[4].restedAfterLastSolve = false;
  bodies[3].angularVelocity = Eigen::Vector3d(0.0, 0.1, 0.0);  // its far corner at 8.7 cm/s
  reach.noteSolved(contacts, bodies);
  EXPECT_TRUE(reach.reached(contacts, {}, bodies, sizes).empty());
}

}  // namespace
}  // namespace polysim::sim
