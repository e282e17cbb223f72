// Contact reuse (collision/contact_reuse.h): a pair in contact that has hardly moved
// against itself keeps its contacts, and what it keeps is what a fresh test would find.
// Every case is a random pair (boxes, spheres, a staple and a cup: convex and not) set in
// contact at a random relative pose and a random place in the world.

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "collision/convex_separation.h"
#include "collision/intersection.h"
#include "collision/shapes.h"
#include "collision/tolerances.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return test::drawnQuaternion([&] { return g(rng); }).normalized().toRotationMatrix();
}

// A rigid motion of size `size`: a translation of length `size` or a turn moving no
// point of a body within `reach` of the origin by more than `size`.
Eigen::Isometry3d smallMotion(std::mt19937& rng, double size, double reach) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const V3 axis = V3::Random().normalized();
  if (std::uniform_int_distribution<int>(0, 1)(rng)) X.translation() = size * axis;
  else X.linear() = Eigen::AngleAxisd(size / reach, axis).toRotationMatrix();
  return X;
}

// Objects "A" and "B" of random shapes, B at a random pose and A touching it: A slides
// along a random direction towards B until the pair is in contact (bisection on the
// distance: separate above, interpenetrating below).
ObjectDatabase randomPairInContact(std::mt19937& rng, const std::vector<std::shared_ptr<PolygonMesh>>& shapes) {
  std::uniform_int_distribution<size_t> pick(0, shapes.size() - 1);
  ObjectDatabase db;
  const auto& meshA = shapes[pick(rng)];
  const auto& meshB = shapes[pick(rng)];
  const Eigen::Isometry3d X_WB = test::pose(4.0 * V3::Random(), randomRotation(rng));
  const Eigen::Matrix3d R_WA = randomRotation(rng);
  const V3 direction = V3::Random().normalized();
  db.add("A", meshA, X_WB, false);
  db.add("B", meshB, X_WB, false);
  double inside = 0.0, apart = 2.0 * (meshA->bounds().sizes().norm() + meshB->bounds().sizes().norm());
  for (int i = 0; i < 100; ++i) {
    const double s = 0.5 * (inside + apart);
    db.objects[0].X_WO = test::pose(X_WB * V3::Zero() + s * direction, R_WA);
    const Status status = test4Intersection(db).status;
    if (status == Status::Contact) return db;
    (status == Status::Separate ? apart : inside) = s;
  }
  ADD_FAILURE() << "no contact found";
  return db;
}

// Convex shapes with separating axes (a box, a hexagonal prism, an icosahedron), a
// convex one with too many faces for them (an icosphere) and two non-convex ones.
std::vector<std::shared_ptr<PolygonMesh>> testShapes() {
  return {std::make_shared<PolygonMesh>(makeBox(V3(1, 0.6, 0.8))), std::make_shared<PolygonMesh>(test::makeHexPrism(0.5, 0.8)),
          std::make_shared<PolygonMesh>(makeIcosphere(0.6, 0)),   std::make_shared<PolygonMesh>(makeIcosphere(0.6, 1)),
          std::make_shared<PolygonMesh>(test::makeStaple()),      std::make_shared<PolygonMesh>(test::makeCup(1.0, 0.6, 0.1, 0.1))};
}

// Whether the pair's verdict is the separating axis test's, the only pairs reuse keeps.
bool keepable(const ObjectDatabase& db) {
  return hasSeparatingAxes(*db.objects[0].mesh) && hasSeparatingAxes(*db.objects[1].mesh);
}

double deepestGap(const PairResult& pair) {
  double deepest = 1e300;
  for (const Contact& c : pair.contacts) deepest = std::min(deepest, c.separation);
  return deepest;
}

// The same contacts: count, types, normals, points and gaps within `tol`.
void expectSameContacts(const PairResult& reused, const PairResult& fresh, double tol, int trial) {
  ASSERT_EQ(reused.contacts.size(), fresh.contacts.size()) << "trial " << trial;
  for (size_t k = 0; k < fresh.contacts.size(); ++k) {
    const Contact &r = reused.contacts[k], &f = fresh.contacts[k];
    EXPECT_EQ(r.type, f.type) << "trial " << trial;
    EXPECT_TRUE(test::near(r.normal, f.normal, 1e-9)) << "trial " << trial;
    ASSERT_EQ(r.points.size(), f.points.size()) << "trial " << trial;
    for (size_t i = 0; i < f.points.size(); ++i) {
      EXPECT_TRUE(test::near(r.points[i], f.points[i], tol)) << "trial " << trial;
      EXPECT_NEAR(r.gapAt(i), f.gapAt(i), tol) << "trial " << trial;
    }
  }
}

TEST(ContactReuse, APairMovedRigidlyKeepsItsContactsCarriedWithIt) {
  std::mt19937 rng(20261130);
  const auto shapes = testShapes();
  int reusedPairs = 0, keepablePairs = 0;
  for (int trial = 0; trial < 60; ++trial) {
    ObjectDatabase db = randomPairInContact(rng, shapes);
    keepablePairs += keepable(db);
    IntersectionWorkspace ws;
    ws.reuse.enable();
    const IntersectionResult first = test4Intersection(db, ws);
    ASSERT_EQ(first.status, Status::Contact) << "trial " << trial;
    EXPECT_EQ(first.pairsReused, 0);
    // Both objects carried by one large motion: nothing moved relative to the other.
    const Eigen::Isometry3d carry = test::pose(3.0 * V3::Random(), randomRotation(rng));
    for (ObjNode& o : db.objects) o.X_WO = carry * o.X_WO;
    const IntersectionResult again = test4Intersection(db, ws);
    const IntersectionResult fresh = test4Intersection(db);
    ASSERT_EQ(again.pairsReused, keepable(db) ? 1 : 0) << "trial " << trial;
    if (keepable(db)) {
      EXPECT_EQ(again.polygonPairsTested, 0) << "trial " << trial;
    }
    ASSERT_EQ(again.pairs.size(), 1u);
    EXPECT_EQ(again.pairs[0].status, fresh.pairs[0].status);
    expectSameContacts(again.pairs[0], fresh.pairs[0], 1e-9, trial);
    reusedPairs += again.pairsReused;
  }
  EXPECT_EQ(reusedPairs, keepablePairs);
  EXPECT_GE(keepablePairs, 8);
}

TEST(ContactReuse, ReusedWithinTheDriftAndTestedAfreshBeyondIt) {
  std::mt19937 rng(7);
  const auto shapes = testShapes();
  int within = 0, beyond = 0, keepablePairs = 0;
  for (int trial = 0; trial < 80; ++trial) {
    ObjectDatabase db = randomPairInContact(rng, shapes);
    keepablePairs += keepable(db);
    const double eps = db.tolerance, limit = kContactReuseFraction * eps;
    IntersectionWorkspace ws;
    ws.reuse.enable();
    const PairResult kept = test4Intersection(db, ws).pairs.at(0);
    const Eigen::Isometry3d X_WA = db.objects[0].X_WO;
    double reach = 0.0;
    for (const V3& v : db.objects[0].mesh->vertices()) reach = std::max(reach, v.norm());
    // A moves relative to B by half the limit: kept, each gap within the drift of a fresh test's.
    db.objects[0].X_WO = X_WA * smallMotion(rng, 0.5 * limit, reach);
    const IntersectionResult near = test4Intersection(db, ws);
    const IntersectionResult fresh = test4Intersection(db);
    ASSERT_EQ(near.status, fresh.status) << "trial " << trial;
    if (near.pairsReused == 1) {
      ++within;
      EXPECT_NEAR(deepestGap(near.pairs[0]), deepestGap(fresh.pairs[0]), 0.5 * limit + 1e-12) << "trial " << trial;
      expectSameContacts(near.pairs[0], kept, 1e-9 * (1 + db.objects[1].X_WO.translation().norm()), trial);
    }
    // Twice the limit from where it was kept: tested afresh.
    db.objects[0].X_WO = X_WA * smallMotion(rng, 2.0 * limit, reach);
    const IntersectionResult far = test4Intersection(db, ws);
    EXPECT_EQ(far.pairsReused, 0) << "trial " << trial;
    beyond += far.pairsReused == 0;
  }
  // A pair kept at the band's very edge is tested afresh even within the drift; most are not.
  EXPECT_GT(within, 3 * keepablePairs / 4);
  EXPECT_GT(keepablePairs, 15);
  EXPECT_EQ(beyond, 80);
}

TEST(ContactReuse, NeverAcrossMeshesTolerancesOrWhenOff) {
  std::mt19937 rng(11);
  const auto shapes = testShapes();
  ObjectDatabase db = randomPairInContact(rng, shapes);
  IntersectionWorkspace off;
  test4Intersection(db, off);
  EXPECT_EQ(test4Intersection(db, off).pairsReused, 0);

  IntersectionWorkspace ws;
  ws.reuse.enable();
  test4Intersection(db, ws);
  EXPECT_EQ(test4Intersection(db, ws).pairsReused, 1);
  ObjectDatabase wider = db;  // the same objects judged in a wider band: a result of its own
  wider.tolerance = 10 * db.tolerance;
  EXPECT_EQ(test4Intersection(wider, ws).pairsReused, 0);
  EXPECT_EQ(test4Intersection(db, ws).pairsReused, 1);  // the first band's result is still kept
  ObjectDatabase other = db;  // same ids, another mesh for A
  other.objects[0].mesh = std::make_shared<PolygonMesh>(*db.objects[0].mesh);
  EXPECT_EQ(test4Intersection(other, ws).pairsReused, 0);
  ObjectDatabase anonymous = db;  // objects not added by the database have no id
  for (ObjNode& o : anonymous.objects) o.id = -1;
  EXPECT_EQ(test4Intersection(anonymous, ws).pairsReused, 0);
}

TEST(ContactReuse, AVerdictOnlyTestReusesTheStatusWithoutContacts) {
  std::mt19937 rng(5);
  const auto shapes = testShapes();
  ObjectDatabase db = randomPairInContact(rng, shapes);
  IntersectionWorkspace ws;
  ws.reuse.enable();
  test4Intersection(db, ws);
  IntersectionOptions verdict;
  verdict.contacts = false;
  const IntersectionResult r = test4Intersection(db, ws, verdict);
  EXPECT_EQ(r.pairsReused, 1);
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0].status, Status::Contact);
  EXPECT_TRUE(r.pairs[0].contacts.empty());
}

// A box kept lying on a floor just inside either edge of the band, then moved by half the
// drift limit across that edge: out of contact, or into interpenetration. It is tested
// afresh and the status follows the fresh test.
TEST(ContactReuse, AtTheBandsEdgeAPairIsTestedAfresh) {
  const auto box = std::make_shared<PolygonMesh>(makeBox(V3(1, 1, 1)));
  const auto floor = std::make_shared<PolygonMesh>(makeBox(V3(4, 4, 1)));
  for (const Eigen::Isometry3d& X : {Eigen::Isometry3d::Identity(), test::pose(V3(2, -1, 3), Eigen::Matrix3d(Eigen::AngleAxisd(0.7, V3(1, 2, 0).normalized())))}) {
    ObjectDatabase db;
    const double eps = db.tolerance, limit = kContactReuseFraction * eps;
    db.add("box", box, Eigen::Isometry3d::Identity(), false);
    db.add("floor", floor, X * Eigen::Isometry3d(Eigen::Translation3d(0, 0, -1)), true);
    for (const auto& [kept, moved, after] : {std::tuple{eps - 0.3 * limit, eps + 0.2 * limit, Status::Separate},
                                             std::tuple{-eps + 0.3 * limit, -eps - 0.2 * limit, Status::Interpenetrating}}) {
      IntersectionWorkspace ws;
      ws.reuse.enable();
      db.objects[0].X_WO = X * Eigen::Isometry3d(Eigen::Translation3d(0, 0, kept));
      ASSERT_EQ(test4Intersection(db, ws).status, Status::Contact);
      db.objects[0].X_WO = X * Eigen::Isometry3d(Eigen::Translation3d(0, 0, moved));
      EXPECT_EQ(test4Intersection(db).status, after);
      const IntersectionResult r = test4Intersection(db, ws);
      EXPECT_EQ(r.pairsReused, 0);
      EXPECT_EQ(r.status, after);
    }
  }
}

// Random pairs, convex and not, kept just short of interpenetrating and then moved
// across that edge by less than the drift limit: the status follows a fresh test. The
// edge is found by bisection along a random direction between a state in contact and
// one interpenetrating. For a cup or a staple the verdict is the polygons' depth, which
// may lie deeper than any contact's gap: a guard that read only the gaps kept such a
// pair in contact after a fresh test found it interpenetrating, and a column of cups
// went on from that state until its next interval began interpenetrating.
TEST(ContactReuse, APairMovedAcrossTheInterpenetrationEdgeWithinTheDriftIsTestedAfresh) {
  std::mt19937 rng(31);
  const auto shapes = testShapes();
  int crossed = 0;
  for (int trial = 0; trial < 80; ++trial) {
    ObjectDatabase db = randomPairInContact(rng, shapes);
    const double eps = db.tolerance, limit = kContactReuseFraction * eps;
    const Eigen::Isometry3d inContact = db.objects[0].X_WO;
    const V3 toB = (db.objects[1].X_WO.translation() - inContact.translation()).normalized();
    const auto at = [&](double s) {
      db.objects[0].X_WO = inContact;
      db.objects[0].X_WO.translation() += s * toB;
      return test4Intersection(db).status;
    };
    double contact = 0.0, inside = 0.05;
    if (at(inside) != Status::Interpenetrating) continue;
    while (inside - contact > 0.05 * limit) {
      const double s = 0.5 * (contact + inside);
      const Status st = at(s);
      if (st == Status::Separate) break;  // not one edge along this line
      (st == Status::Contact ? contact : inside) = s;
    }
    if (inside - contact > 0.05 * limit || at(contact) != Status::Contact) continue;
    IntersectionWorkspace ws;
    ws.reuse.enable();
    db.objects[0].X_WO = inContact;
    db.objects[0].X_WO.translation() += contact * toB;
    ASSERT_EQ(test4Intersection(db, ws).status, Status::Contact) << "trial " << trial;
    ASSERT_EQ(at(inside), Status::Interpenetrating) << "trial " << trial;  // moved by under 0.05 of the limit
    EXPECT_EQ(test4Intersection(db, ws).status, Status::Interpenetrating)
        << "trial " << trial << ", convex " << db.objects[0].mesh->convex() << db.objects[1].mesh->convex();
    ++crossed;
  }
  EXPECT_GT(crossed, 40);
}

}  // namespace
}  // namespace polysim::collision
