// Containment (collision/containment.h): an object wholly inside a closed object meets
// none of its polygons, yet the pair interpenetrates. Checked in every world frame, with
// the pair given both ways, against convex and non-convex outer objects whose insides are
// known exactly, and on seeded random placements against the analytic inside test.

#include "collision/containment.h"

#include <gtest/gtest.h>

#include <random>

#include "collision/intersection.h"
#include "collision/shapes.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

std::shared_ptr<const PolygonMesh> mesh(const MeshData& data) { return std::make_shared<const PolygonMesh>(data); }

Eigen::Isometry3d at(const V3& p, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = p;
  return X;
}

// test4Intersection on inner and outer placed in `frame`, the pair given in `order`.
PairResult pairOf(const std::shared_ptr<const PolygonMesh>& inner, const Eigen::Isometry3d& X_inner,
                  const std::shared_ptr<const PolygonMesh>& outer, const Eigen::Isometry3d& X_outer,
                  const Eigen::Isometry3d& frame, bool innerFirst) {
  ObjectDatabase db;
  if (innerFirst) db.add("inner", inner, frame * X_inner, false), db.add("outer", outer, frame * X_outer, false);
  else db.add("outer", outer, frame * X_outer, false), db.add("inner", inner, frame * X_inner, false);
  const IntersectionResult r = test4Intersection(db);
  return r.pairs.empty() ? PairResult{} : r.pairs.front();
}

// The verdict and depth, the same in every frame and with the pair swapped.
void expectEverywhere(const std::shared_ptr<const PolygonMesh>& inner, const Eigen::Isometry3d& X_inner,
                      const std::shared_ptr<const PolygonMesh>& outer, const Eigen::Isometry3d& X_outer, Status status,
                      double depth = 0.0) {
  for (const test::NamedFrame& frame : test::worldFrames())
    for (bool innerFirst : {true, false}) {
      SCOPED_TRACE(frame.name + (innerFirst ? ", inner first" : ", outer first"));
      const PairResult p = pairOf(inner, X_inner, outer, X_outer, frame.X, innerFirst);
      EXPECT_EQ(p.status, status);
      if (status == Status::Interpenetrating) {
        EXPECT_NEAR(p.depth, depth, 1e-9);
      }
    }
}

// Two convex objects are judged by their penetration depth (the separating axis test),
// which needs no polygons to meet: the least translation that parts them.
TEST(Containment, ASmallBoxInsideABigOneInterpenetratesByTheTranslationThatPartsThem) {
  // A 0.2 m box centred in a 2 m box: its far side is 1.1 m from the nearest face.
  expectEverywhere(mesh(makeBox(V3(0.2, 0.2, 0.2))), at(V3(0, 0, 0)), mesh(makeBox(V3(2, 2, 2))), at(V3(0, 0, 0)),
                   Status::Interpenetrating, 1.1);
  // Off centre along x: its side at x = 0.5 must pass x = 1.
  expectEverywhere(mesh(makeBox(V3(0.2, 0.2, 0.2))), at(V3(0.6, 0, 0)), mesh(makeBox(V3(2, 2, 2))), at(V3(0, 0, 0)),
                   Status::Interpenetrating, 0.5);
}

// Within the tolerance of the wall from inside, the box's far side is still deep inside
// the solid: interpenetrating (SPEC: a feature more than the tolerance inside), not a
// contact.
TEST(Containment, JustInsideAWallIsStillInterpenetrating) {
  const double eps = ObjectDatabase{}.tolerance;
  expectEverywhere(mesh(makeBox(V3(0.2, 0.2, 0.2))), at(V3(0.9 - 0.5 * eps, 0, 0)), mesh(makeBox(V3(2, 2, 2))),
                   at(V3(0, 0, 0)), Status::Interpenetrating, 0.2 + 0.5 * eps);
}

TEST(Containment, ACupsCavityIsOutsideItsSolidAndItsFloorInside) {
  const auto cup = mesh(test::makeCup(1.0, 1.5, 0.2, 0.3));  // cavity: |x|, |y| < 0.8, z in (0.3, 1.5)
  const auto pebble = mesh(makeBox(V3(0.1, 0.1, 0.1)));
  expectEverywhere(pebble, at(V3(0, 0, 0.8)), cup, at(V3(0, 0, 0)), Status::Separate);                // in the cavity
  expectEverywhere(pebble, at(V3(0.2, -0.3, 0.15)), cup, at(V3(0, 0, 0)), Status::Interpenetrating,  // in the floor
                   0.1);
  expectEverywhere(pebble, at(V3(0.9, 0, 1.0)), cup, at(V3(0, 0, 0)), Status::Interpenetrating, 0.05);  // in a wall
}

TEST(Containment, AnLsFootHoldsABoxAndItsNotchDoesNot) {
  const auto L = mesh(test::makeL());  // solid: x in [0,2], z in [0,1]; and x in [0,1], z in [1,2]; y in [0,1]
  const auto box = mesh(makeBox(V3(0.2, 0.2, 0.2)));
  const Eigen::Quaterniond turned(Eigen::AngleAxisd(0.4, V3(1, 2, 3).normalized()));
  // In the foot, away from the upright: each corner's depth is its distance to the foot's
  // faces, and the deepest corner's is the pair's.
  double depth = 0.0;
  for (const V3& v : box->vertices()) {
    const V3 corner = V3(1.5, 0.5, 0.45) + turned * v;
    depth = std::max(depth, std::min(corner.minCoeff(), (V3(2, 1, 1) - corner).minCoeff()));
  }
  expectEverywhere(box, at(V3(1.5, 0.5, 0.45), turned), L, at(V3(0, 0, 0)), Status::Interpenetrating, depth);
  expectEverywhere(box, at(V3(1.5, 0.5, 1.5), turned), L, at(V3(0, 0, 0)), Status::Separate);  // in the notch
}

TEST(Containment, AnOpenMeshHoldsNothing) {
  MeshData open = makeBox(V3(2, 2, 2));
  open.faces.pop_back();  // a box without its lid
  ObjectDatabase db;
  db.add("inner", mesh(makeBox(V3(0.2, 0.2, 0.2))), at(V3(0, 0, 0)), false);
  db.add("open", std::make_shared<const PolygonMesh>(open), at(V3(0, 0, 0)), true);
  EXPECT_EQ(test4Intersection(db).status, Status::Separate);
}

// Seeded random placements of a small turned box in and around a big box and an L: the
// verdict is the analytic one (inside the solid by more than the box's reach: contained;
// farther than that outside it: separate); placements near a surface are left out.
TEST(Containment, SeededPlacementsAgreeWithTheAnalyticInside) {
  const auto small = mesh(makeBox(V3(0.2, 0.2, 0.2)));
  const double reach = 0.1 * std::sqrt(3.0) + 1e-3;
  struct Outer {
    std::shared_ptr<const PolygonMesh> mesh;
    Eigen::AlignedBox3d around;
    double (*depth)(const V3&);  // > 0 inside the solid: distance to its surface
  };
  auto boxDepth = [](const V3& p) { return 1.0 - p.cwiseAbs().maxCoeff(); };
  auto lDepth = [](const V3& p) {
    auto inBox = [&](const V3& lo, const V3& hi) { return std::min((p - lo).minCoeff(), (hi - p).minCoeff()); };
    const double foot = inBox(V3(0, 0, 0), V3(2, 1, 1)), upright = inBox(V3(0, 0, 1), V3(1, 1, 2));
    return std::max(foot, upright);  // exact wherever it decides (|depth| > reach)
  };
  const Outer outers[] = {{mesh(makeBox(V3(2, 2, 2))), Eigen::AlignedBox3d(V3(-1.5, -1.5, -1.5), V3(1.5, 1.5, 1.5)), boxDepth},
                          {mesh(test::makeL()), Eigen::AlignedBox3d(V3(-0.5, -0.5, -0.5), V3(2.5, 1.5, 2.5)), lDepth}};
  std::mt19937 rng(20261129);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int inside = 0, outside = 0;
  for (const Outer& o : outers)
    for (int k = 0; k < 400; ++k) {
      const V3 p = o.around.min() + (o.around.max() - o.around.min()).cwiseProduct(test::drawnVector([&] { return unit(rng); }));
      const double d = o.depth(p);
      if (std::abs(d) < reach) continue;
      const Eigen::Quaterniond drawn = test::drawnQuaternion([&] { return unit(rng); });
      const Eigen::Quaterniond q = Eigen::Quaterniond(drawn.w(), drawn.x() - 0.5, drawn.y() - 0.5, drawn.z() - 0.5).normalized();
      const PairResult r = pairOf(small, at(p, q), o.mesh, at(V3(0, 0, 0)), test::worldFrames()[2].X, k % 2 == 0);
      EXPECT_EQ(r.status, d > 0 ? Status::Interpenetrating : Status::Separate) << "at " << p.transpose();
      (d > 0 ? inside : outside) += 1;
    }
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 50);
}

TEST(Containment, InsideTestCountsCrossingsThroughEdgesOnce) {
  // Points whose first ray leaves the box through an edge (two faces share the crossing)
  // or a corner (three do): the test casts again and still says inside.
  const PolygonMesh box(makeBox(V3(2, 2, 2)));
  EXPECT_TRUE(insideClosedMesh(box, V3(0, 0, 0)));
  EXPECT_TRUE(insideClosedMesh(box, V3(0.999, 0.999, 0.999)));
  EXPECT_FALSE(insideClosedMesh(box, V3(1.001, 0, 0)));
  const V3 d = V3(1.0, std::sqrt(2.0), std::sqrt(3.0)).normalized();
  EXPECT_TRUE(insideClosedMesh(box, V3(1, 1, 0) - 0.5 * d));  // through the edge x = y = 1
  EXPECT_TRUE(insideClosedMesh(box, V3(1, 1, 1) - 1.5 * d));  // through the corner (1, 1, 1)
  EXPECT_FALSE(insideClosedMesh(box, V3(1, 1, 0) + 0.5 * d));  // outside, on the same line
}

}  // namespace
}  // namespace polysim::collision
