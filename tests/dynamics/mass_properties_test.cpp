#include "dynamics/mass_properties.h"

#include <gtest/gtest.h>

#include "collision/shapes.h"
#include "tests/test_support.h"

namespace polysim::dynamics {
namespace {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

MassProperties of(const collision::MeshData& m, double density = 1.0) {
  return computeMassProperties(m.vertices, m.faces, density);
}

// A solid cuboid of the given sides and centre: inertia about its own centre.
M3 cuboidInertia(double mass, const V3& size) {
  return mass / 12.0 *
         V3(size.y() * size.y() + size.z() * size.z(), size.x() * size.x() + size.z() * size.z(),
            size.x() * size.x() + size.y() * size.y())
             .asDiagonal();
}

// Parallel axis theorem: inertia about a point at offset d from the centre of mass.
M3 shifted(const M3& I, double mass, const V3& d) { return I + mass * (d.squaredNorm() * M3::Identity() - d * d.transpose()); }

::testing::AssertionResult near(const M3& a, const M3& b, double tol) {
  if ((a - b).cwiseAbs().maxCoeff() <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\n" << a << "\nvs\n" << b;
}

TEST(MassProperties, Box) {
  const V3 size(1, 2, 3);
  const MassProperties p = of(collision::makeBox(size), 500.0);
  EXPECT_NEAR(p.volume, 6.0, 1e-12);
  EXPECT_NEAR(p.mass, 3000.0, 1e-9);
  EXPECT_TRUE(test::near(p.centerOfMass, V3::Zero(), 1e-12));
  EXPECT_TRUE(near(p.inertia, cuboidInertia(3000.0, size), 1e-9));
}

TEST(MassProperties, Tetrahedron) {
  collision::MeshData t;
  t.vertices = {V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)};
  t.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const MassProperties p = of(t);
  EXPECT_NEAR(p.volume, 1.0 / 6.0, 1e-15);
  EXPECT_TRUE(test::near(p.centerOfMass, V3(0.25, 0.25, 0.25), 1e-15));
  // About the centre: 1/80 on the diagonal, +1/480 off it (integrals of x^2, xy over the tetrahedron).
  M3 expected = M3::Constant(1.0 / 480.0);
  expected.diagonal().setConstant(1.0 / 80.0);
  EXPECT_TRUE(near(p.inertia, expected, 1e-15));
}

TEST(MassProperties, NonConvexL) {
  // The L is a 2x1x1 foot (centre (1, .5, .5)) and a 1x1x1 upright (centre (.5, .5, 1.5)).
  const MassProperties p = of(test::makeL(), 2.0);
  const V3 footCentre(1, 0.5, 0.5), uprightCentre(0.5, 0.5, 1.5);
  const V3 com = (2 * footCentre + uprightCentre) / 3;
  EXPECT_NEAR(p.mass, 6.0, 1e-12);
  EXPECT_TRUE(test::near(p.centerOfMass, com, 1e-12));
  const M3 expected = shifted(cuboidInertia(4.0, V3(2, 1, 1)), 4.0, footCentre - com) +
                      shifted(cuboidInertia(2.0, V3(1, 1, 1)), 2.0, uprightCentre - com);
  EXPECT_TRUE(near(p.inertia, expected, 1e-12));
}

TEST(MassProperties, MovedMeshesMoveTheirPropertiesAlong) {
  for (const collision::MeshData& base : {collision::makeBox(V3(1, 2, 3)), test::makeL(), test::makeStaple()}) {
    const MassProperties p = of(base);
    for (const test::NamedFrame& f : test::worldFrames()) {
      collision::MeshData moved = base;
      for (V3& v : moved.vertices) v = f.X * v;
      const MassProperties q = of(moved);
      EXPECT_NEAR(q.volume, p.volume, 1e-12) << f.name;
      EXPECT_TRUE(test::near(q.centerOfMass, f.X * p.centerOfMass, 1e-12)) << f.name;
      EXPECT_TRUE(near(q.inertia, f.X.linear() * p.inertia * f.X.linear().transpose(), 1e-12)) << f.name;
    }
  }
}

TEST(MassProperties, IcosphereConvergesToASphere) {
  double previous = 1.0;
  for (int level = 1; level <= 5; ++level) {
    const MassProperties p = of(collision::makeIcosphere(1.0, level));
    const double ratio = p.inertia(0, 0) / p.mass;  // 2/5 r^2 for a solid sphere
    const double error = std::abs(ratio - 0.4) / 0.4;
    EXPECT_LT(error, previous) << "level " << level;
    EXPECT_NEAR(p.inertia(1, 1), p.inertia(0, 0), 1e-9 * p.inertia(0, 0));
    EXPECT_NEAR(p.inertia(0, 1), 0.0, 1e-9 * p.inertia(0, 0));
    previous = error;
  }
  EXPECT_LT(previous, 1e-3);
}

TEST(MassProperties, GivenMassScalesInertia) {
  const MassProperties p = withMass(of(collision::makeBox(V3(1, 1, 1)), 1000.0), 2.0);
  EXPECT_EQ(p.mass, 2.0);
  EXPECT_TRUE(near(p.inertia, cuboidInertia(2.0, V3(1, 1, 1)), 1e-12));
}

}  // namespace
}  // namespace polysim::dynamics
