// Speculative contacts (sim/speculative_contacts.h): which pairs the widened test gives
// the solver, and a box tipping onto its face without backing up for the touch.

#include "sim/speculative_contacts.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <random>

#include "collision/shapes.h"
#include "tests/sim/scenario_support.h"

namespace polysim::sim {
namespace {

using collision::PairResult;
using collision::Status;
using test::V3;

std::pair<int, int> idsOf(const PairResult& p) { return {std::min(p.a, p.b), std::max(p.a, p.b)}; }

// Unit boxes along x: box 0 at the origin, box 1 with a 1 cm gap beyond it, box 2 with a
// 3 cm gap before it (beyond the 2 cm reach).
collision::ObjectDatabase threeBoxes() {
  collision::ObjectDatabase db;
  const auto box = std::make_shared<collision::PolygonMesh>(collision::makeBox(V3(1, 1, 1)));
  for (double x : {0.0, 1.01, -1.03}) db.add("box", box, Eigen::Isometry3d(Eigen::Translation3d(x, 0, 0)), false);
  return db;
}

const auto everyPair = [](const PairResult&) { return true; };
const auto allMoving = [](int) { return SpeculativeRole::Moving; };

// Two unit boxes at poses taken from a run, replayed in `count` seeded frames (the
// world's own first), so that a check does not hang on one placement: the database of
// the two, box 0 at `first`, for each frame in turn.
template <typename Check>
void inSeededFrames(const Eigen::Isometry3d& first, const Eigen::Isometry3d& second, unsigned seed, int count, Check check) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto box = std::make_shared<collision::PolygonMesh>(collision::makeBox(V3(1, 1, 1)));
  for (int k = 0; k < count; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    const Eigen::Isometry3d frame = k == 0 ? Eigen::Isometry3d::Identity()
                                           : Eigen::Translation3d(5 * unit(rng), 5 * unit(rng), 5 * unit(rng)) *
                                                 Eigen::AngleAxisd(M_PI * unit(rng), V3(unit(rng), unit(rng), 1).normalized());
    collision::ObjectDatabase db;
    db.add("first", box, frame * first, false);
    db.add("second", box, frame * second, false);
    check(db);
  }
}

TEST(SpeculativeContacts, PairsWithinTheReachComeWithTheirGaps) {
  collision::ObjectDatabase db = threeBoxes();
  collision::IntersectionWorkspace ws;
  const std::vector<PairResult> found = withSpeculativeContacts(db, ws, kSpeculativeReach, {}, {}, allMoving, everyPair);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(idsOf(found[0]), std::make_pair(0, 1));
  EXPECT_EQ(found[0].status, Status::Contact);
  ASSERT_FALSE(found[0].contacts.empty());
  for (const collision::Contact& c : found[0].contacts) {
    EXPECT_NEAR(std::abs(c.normal.x()), 1.0, 1e-12);
    for (size_t i = 0; i < c.points.size(); ++i) EXPECT_NEAR(c.gapAt(i), 0.01, 1e-9);
  }
  EXPECT_EQ(db.tolerance, 1e-4) << "the database keeps its own tolerance";
}

TEST(SpeculativeContacts, StillAndLeftObjectsAndRefusedPairsAreNotWidened) {
  collision::ObjectDatabase db = threeBoxes();
  collision::IntersectionWorkspace ws;
  const auto still = [](int) { return SpeculativeRole::Still; };
  EXPECT_TRUE(withSpeculativeContacts(db, ws, kSpeculativeReach, {}, {}, still, everyPair).empty());
  const auto leftOne = [](int k) { return k == 1 ? SpeculativeRole::Left : SpeculativeRole::Moving; };
  EXPECT_TRUE(withSpeculativeContacts(db, ws, kSpeculativeReach, {}, {}, leftOne, everyPair).empty());
  const auto refuse = [](const PairResult&) { return false; };
  EXPECT_TRUE(withSpeculativeContacts(db, ws, kSpeculativeReach, {}, {}, allMoving, refuse).empty());
  // One moving, one still: still tested against each other.
  const auto oneMoving = [](int k) { return k == 0 ? SpeculativeRole::Moving : SpeculativeRole::Still; };
  EXPECT_EQ(withSpeculativeContacts(db, ws, kSpeculativeReach, {}, {}, oneMoving, everyPair).size(), 1u);
}

// Two top boxes of neighbouring tilted towers (pile of 1000, seed 15, poses at 11.63 s),
// 6 mm apart at their nearest, in seeded frames: the widened test reads the lower box's
// top corner, 1.5 cm beside the higher box's bottom face and just above its plane, as
// 30 um deep along that face's normal. The detector finds the pair apart (not touching),
// so the solver is given no gap below the tolerance: given the overlap, it held the
// higher box tilted on that corner and the tower rocked for good.
TEST(SpeculativeContacts, APairNotTouchingIsGivenNoGapBelowTheTolerance) {
  const Eigen::Isometry3d lower = Eigen::Translation3d(-2.3035844, 0.5704868, 8.5012177) *
                                  Eigen::Quaterniond(0.979258, 0.001008, -0.001782, -0.202609).normalized();
  const Eigen::Isometry3d higher = Eigen::Translation3d(-2.5097177, -0.6221664, 9.5002545) *
                                   Eigen::Quaterniond(0.999751, 0.000065, -0.001113, 0.022276).normalized();
  inSeededFrames(lower, higher, 3, 8, [](const collision::ObjectDatabase& db) {
    collision::IntersectionWorkspace ws;
    ASSERT_EQ(collision::test4Intersection(db, ws).status, Status::Separate);
    const std::vector<PairResult> found = withSpeculativeContacts(db, ws, kSpeculativeReach, {}, {}, allMoving, everyPair);
    ASSERT_EQ(found.size(), 1u);
    int points = 0;
    for (const collision::Contact& c : found[0].contacts) {
      EXPECT_GE(c.separation, db.tolerance);
      for (size_t i = 0; i < c.points.size(); ++i, ++points) EXPECT_GE(c.gapAt(i), db.tolerance);
    }
    EXPECT_GT(points, 0);
  });
}

// A touching pair the test widens is replaced (once, under body indices); one it does
// not find stays as it was given.
TEST(SpeculativeContacts, TouchingPairsAreKeptOrWidenedAndMappedToBodies) {
  collision::ObjectDatabase db = threeBoxes();
  collision::IntersectionWorkspace ws;
  const std::vector<int> bodyOf = {10, 11, 12};
  PairResult touching01, touching02;
  touching01.a = 11, touching01.b = 10, touching01.status = Status::Contact;
  touching02.a = 10, touching02.b = 12, touching02.status = Status::Contact;
  const std::vector<PairResult> found =
      withSpeculativeContacts(db, ws, kSpeculativeReach, bodyOf, {touching01, touching02}, allMoving, everyPair);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(idsOf(found[0]), std::make_pair(10, 11));
  EXPECT_FALSE(found[0].contacts.empty()) << "widened";
  EXPECT_EQ(found[1].a, 10);
  EXPECT_EQ(found[1].b, 12);
  EXPECT_TRUE(found[1].contacts.empty()) << "as given";
}

// A touching pair that the widened test finds keeps, beside the widened contacts, each of
// the detector's own contacts whose normal none of them shares (given here under the
// pair's other order, so with the normal reversed): near a face's rim the widened test
// may see a face where the detector saw two edges crossing, and a solve on the face's
// normal alone let the edges sink past the tolerance (a box landing spinning on another:
// one event after another, each a few microseconds on, to the event bound).
TEST(SpeculativeContacts, TouchingPairsKeepTheDetectorsContactsTheWidenedOnesMiss) {
  collision::ObjectDatabase db = threeBoxes();
  collision::IntersectionWorkspace ws;
  const std::vector<int> bodyOf = {10, 11, 12};
  collision::Contact alongX, crossing;
  alongX.normal = V3::UnitX();  // from body 10 towards 11: the widened contacts' normal, reversed
  alongX.addPoint(V3(0.5, 0, 0), 0.0);
  crossing.normal = V3(0.6, 0.0, 0.8);
  crossing.addPoint(V3(0.5, 0.5, 0.5), -5e-5);
  PairResult touching;
  touching.a = 11, touching.b = 10, touching.status = Status::Contact, touching.contacts = {alongX, crossing};
  const std::vector<PairResult> found = withSpeculativeContacts(db, ws, kSpeculativeReach, bodyOf, {touching}, allMoving, everyPair);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_EQ(found[0].a, 10);
  int widened = 0, kept = 0;
  for (const collision::Contact& c : found[0].contacts) {
    if ((c.normal + V3::UnitX()).norm() < 1e-12) {
      ++widened;
      for (size_t i = 0; i < c.points.size(); ++i) EXPECT_NEAR(c.gapAt(i), 0.01, 1e-9) << "the widened one, not the given one";
    }
    if ((c.normal + crossing.normal).norm() < 1e-12) {
      ++kept;
      EXPECT_EQ(c.separation, -5e-5);
    }
  }
  EXPECT_GE(widened, 1);
  EXPECT_EQ(kept, 1);
  EXPECT_EQ(static_cast<int>(found[0].contacts.size()), widened + kept);
}

// A box leaning across three columns on the box below one corner (pile of 1000, seed 22,
// poses at 10.05 s), in seeded frames: the detector finds the corner 35 um above the
// face, and the widened test read it 0.6 mm deep along a normal 2.5 degrees off the
// face's. The solver pushed the box out of that overlap every few steps: it crept at a
// few mm/s for 15 s and kept its island of 100 boxes awake. No widened gap is below the
// detector's deepest.
TEST(SpeculativeContacts, ATouchingPairIsGivenNoGapBelowTheDetectorsDeepest) {
  const Eigen::Isometry3d below = Eigen::Translation3d(2.237067243844, 0.759640914366, 8.499880097085) *
                                  Eigen::Quaterniond(0.999995161793, 6.443451e-06, -5.516778e-06, -0.003110678239).normalized();
  const Eigen::Isometry3d leaning = Eigen::Translation3d(2.225823322935, 1.684140398374, 9.338964514152) *
                                    Eigen::Quaterniond(0.877798610112, 0.463927687594, 0.113642702596, 0.036414789786).normalized();
  inSeededFrames(below, leaning, 5, 8, [](const collision::ObjectDatabase& db) {
    collision::IntersectionWorkspace ws;
    const collision::IntersectionResult detected = collision::test4Intersection(db, ws);
    ASSERT_EQ(detected.status, Status::Contact);
    ASSERT_EQ(detected.pairs.size(), 1u);
    double deepest = INFINITY;
    for (const collision::Contact& c : detected.pairs[0].contacts) deepest = std::min(deepest, c.separation);
    EXPECT_GT(deepest, 0.0) << "the corner is above the face";
    const std::vector<PairResult> found =
        withSpeculativeContacts(db, ws, kSpeculativeReach, {}, detected.pairs, allMoving, everyPair);
    ASSERT_EQ(found.size(), 1u);
    int points = 0;
    for (const collision::Contact& c : found[0].contacts) {
      EXPECT_GE(c.separation, deepest);
      for (size_t i = 0; i < c.points.size(); ++i, ++points) EXPECT_GE(c.gapAt(i), deepest);
    }
    EXPECT_GT(points, 0);
  });
}

// A detector's contact the widened ones share a normal with is still kept when they put
// the pair's touch elsewhere across that normal: where two edges lie nearly parallel the
// widened test placed their crossing 1.8 cm along them from the detector's, and the
// solver held that point apart while the detector's closed (pile of 1000, seed 6: every
// event of a step stalled at once). Here box 1 stands turned by 45 degrees, its vertical
// edge 1 cm from box 0's face: the widened contact is that edge's line, x = 0.5, y = 0.
TEST(SpeculativeContacts, TouchingPairsKeepTheDetectorsContactsTheWidenedOnesPutElsewhere) {
  collision::ObjectDatabase db;
  const auto box = std::make_shared<collision::PolygonMesh>(collision::makeBox(V3(1, 1, 1)));
  db.add("box", box, Eigen::Isometry3d::Identity(), false);
  Eigen::Isometry3d turned(Eigen::AngleAxisd(M_PI / 4, V3::UnitZ()));
  turned.translation() = V3(0.51 + std::sqrt(0.5), 0, 0);
  db.add("box", box, turned, false);
  collision::IntersectionWorkspace ws;
  collision::Contact onTheLine, offTheLine;
  onTheLine.normal = offTheLine.normal = V3::UnitX();  // from body 10 towards 11, as given (a = 11)
  onTheLine.addPoint(V3(0.5, 0.0, 0.2), 0.0);
  offTheLine.addPoint(V3(0.5, 0.3, 0.0), -5e-5);
  PairResult touching;
  touching.a = 11, touching.b = 10, touching.status = Status::Contact, touching.contacts = {onTheLine, offTheLine};
  const std::vector<PairResult> found = withSpeculativeContacts(db, ws, kSpeculativeReach, {10, 11}, {touching}, allMoving, everyPair);
  ASSERT_EQ(found.size(), 1u);
  ASSERT_EQ(found[0].a, 10);
  int widened = 0, kept = 0;
  for (const collision::Contact& c : found[0].contacts) {
    ASSERT_LT((c.normal + V3::UnitX()).norm(), 1e-9) << "every contact on the pair's one normal";
    if (std::abs(c.separation - 0.01) < 1e-9) {
      ++widened;
      for (const V3& p : c.points) EXPECT_NEAR(p.y(), 0.0, 1e-9) << "the widened contact is box 1's edge";
    } else {
      ++kept;
      EXPECT_EQ(c.separation, -5e-5) << "the point 0.3 m off the line is kept; the one on it is covered";
      EXPECT_EQ(c.points, offTheLine.points);
    }
  }
  EXPECT_GE(widened, 1);
  EXPECT_EQ(kept, 1);
}

// Events and outcome of a unit box released at rest on one corner or edge on the floor,
// tilted by `tilt` (rad) about the horizontal axis at `heading` (rad), over 3 s at 60 Hz.
struct Tipping {
  int events = 0;
  double deepest = 0.0;  // m
  double rise = 0.0;     // J, above the start
  bool atRest = false;
  double height = 0.0;   // m, of the centre at the end
};

Tipping tipOver(double tilt, double heading, double reach) {
  Scene scene = test::scene("tilted_drop");
  scene.dt = 1.0 / 60;
  scene.contact.speculativeReach = reach;
  BodySpec& box = scene.bodies[1];
  box.orientation = Eigen::AngleAxisd(tilt, V3(std::cos(heading), std::sin(heading), 0));
  double lowest = 0.0;
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5})
      for (double z : {-0.5, 0.5}) lowest = std::min(lowest, (box.orientation * V3(x, y, z)).z());
  box.position = V3(0, 0, -lowest + 5e-5);  // the lowest corner inside the band
  box.velocity.setZero();
  box.angularVelocity.setZero();
  World w(scene);
  const double start = w.energy();
  Tipping t;
  test::runFor(w, 3.0, [&](const StepReport& r) {
    t.events += static_cast<int>(r.events.size());
    t.deepest = std::max(t.deepest, r.penetration);
    t.rise = std::max(t.rise, w.energy() - start);
  });
  t.atRest = w.atRest(1);
  t.height = w.bodies()[1].position.z();
  return t;
}

// Seeded random tilts (0.05 to 0.35 rad about random horizontal axes): the box tips onto
// an edge and its face. With speculative contacts its touches back the world up far
// less often than without (the landing on the face, its turning edge sinking into the
// band), and either way it rests flat at the rest height, never deeper than the
// tolerance and never above its starting energy.
TEST(SpeculativeContacts, ATippingBoxBacksUpLessOftenAndRestsFlat) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> angle(0.05, 0.35), heading(0.0, 2 * M_PI);
  int speculating = 0, backingUp = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const double tilt = angle(random), around = heading(random);
    SCOPED_TRACE("tilt " + std::to_string(tilt) + " rad about heading " + std::to_string(around));
    for (double reach : {kSpeculativeReach, 0.0}) {
      const Tipping t = tipOver(tilt, around, reach);
      (reach > 0 ? speculating : backingUp) += t.events;
      EXPECT_LE(t.deepest, 1e-4);
      EXPECT_LE(t.rise, 1e-6);
      EXPECT_TRUE(t.atRest);
      EXPECT_NEAR(t.height, 0.5, 1e-4);
    }
  }
  EXPECT_LE(2 * speculating, backingUp) << speculating << " events with speculative contacts, " << backingUp << " without";
}

// A box of random size dropped from 0.3 to 1.5 m with a random tilt small enough that,
// when its lowest corner touches, its whole bottom face is within half the reach. The
// landing solve, once it has found the box landed, tests the box's pairs again and gives
// the solver that face: the box lands flat in the one event of its first touch, instead
// of swinging down onto its face and backing up a second time. Half the trials land on
// a resting box of random height, half on the floor.
TEST(SpeculativeContacts, ABoxDroppedNearlyFlatLandsInOneEvent) {
  ::polysim::test::SeededDraws draw(11);
  for (int trial = 0; trial < 12; ++trial) {
    Scene scene = test::scene("tilted_drop", false);
    scene.dt = 1.0 / 60;
    BodySpec& box = scene.bodies[1];
    test::setBoxSize(box, draw.vector(0.4, 1.2));
    const double tilt = draw.between(0.1, 1.0) * 0.5 * kSpeculativeReach / box.boxSize.head<2>().norm();
    const double heading = draw.between(0.0, 2 * M_PI);
    box.orientation = Eigen::AngleAxisd(tilt, V3(std::cos(heading), std::sin(heading), 0));
    double floorTop = 0.0;
    if (trial % 2 == 1) {  // a resting box under it, wider than the one dropped
      BodySpec base = box;
      base.name = "base";
      test::setBoxSize(base, V3(2, 2, draw.between(0.3, 1.0)));
      base.orientation = Eigen::Quaterniond::Identity();
      base.position = V3(0, 0, base.boxSize.z() / 2);
      base.mass = 5.0;
      floorTop = base.boxSize.z();
      scene.bodies.push_back(base);  // `box` no longer refers to the scene's body from here
    }
    BodySpec& dropped = scene.bodies[1];
    dropped.position = draw.vector(V3(-0.3, -0.3, 0.3), V3(0.3, 0.3, 1.5)) + V3(0, 0, floorTop + dropped.boxSize.z() / 2);
    SCOPED_TRACE("trial " + std::to_string(trial) + ": tilt " + std::to_string(tilt) + " rad, size " +
                 std::to_string(dropped.boxSize.x()) + " x " + std::to_string(dropped.boxSize.y()));
    World w(scene);
    const double start = w.energy();
    int events = 0, stepsWithEvents = 0;
    double deepest = 0.0, rise = 0.0;
    test::runFor(w, 2.0, [&](const StepReport& r) {
      events += static_cast<int>(r.events.size());
      stepsWithEvents += !r.events.empty();
      deepest = std::max(deepest, r.penetration);
      rise = std::max(rise, w.energy() - start);
    });
    EXPECT_EQ(events, 1) << "in " << stepsWithEvents << " steps";
    EXPECT_LE(deepest, 1e-4);
    EXPECT_LE(rise, 1e-9);
    EXPECT_TRUE(w.atRest(1));
    EXPECT_NEAR(w.bodies()[1].position.z(), floorTop + dropped.boxSize.z() / 2, 1e-4);
  }
}

}  // namespace
}  // namespace polysim::sim
