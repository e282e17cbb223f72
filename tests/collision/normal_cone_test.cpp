// The directions a unit box can be touched from at its faces, edges and corners.

#include "collision/normal_cone.h"

#include <gtest/gtest.h>

#include "collision/shapes.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;
constexpr double kEps = kDefaultContactTolerance;

class BoxCones : public ::testing::Test {
 protected:
  PolygonMesh box{makeBox(V3(1, 1, 1))};

  Feature faceWithNormal(const V3& n) const {
    for (int f = 0; f < box.faceCount(); ++f)
      if (box.facePlane(f).normal.isApprox(n)) return {Feature::Kind::Face, f};
    return {};
  }
  Feature vertexAt(const V3& p) const {
    for (size_t v = 0; v < box.vertices().size(); ++v)
      if (box.vertices()[v].isApprox(p)) return {Feature::Kind::Vertex, static_cast<int>(v)};
    return {};
  }
  Feature edgeBetween(const V3& p, const V3& q) const {
    for (size_t e = 0; e < box.edges().size(); ++e) {
      const V3& a = box.vertices()[box.edges()[e].v0];
      const V3& b = box.vertices()[box.edges()[e].v1];
      if ((a.isApprox(p) && b.isApprox(q)) || (a.isApprox(q) && b.isApprox(p))) return {Feature::Kind::Edge, static_cast<int>(e)};
    }
    return {};
  }
};

TEST_F(BoxCones, AFaceAdmitsItsNormalOnly) {
  const Feature top = faceWithNormal(V3::UnitZ());
  ASSERT_GE(top.id, 0);
  EXPECT_TRUE(inNormalCone(box, top, V3::UnitZ(), kEps));
  EXPECT_TRUE(inNormalCone(box, top, V3(kEps, 0, 1).normalized(), kEps));  // tilted within the band over 1 m
  EXPECT_FALSE(inNormalCone(box, top, V3(0.01, 0, 1).normalized(), kEps));
  EXPECT_FALSE(inNormalCone(box, top, V3::UnitX(), kEps));
  EXPECT_FALSE(inNormalCone(box, top, -V3::UnitZ(), kEps));
}

TEST_F(BoxCones, AnEdgeAdmitsTheWedgeBetweenItsFaces) {
  const Feature edge = edgeBetween(V3(0.5, -0.5, 0.5), V3(0.5, 0.5, 0.5));  // top face meets +x face
  ASSERT_GE(edge.id, 0);
  for (const V3& n : {V3(0, 0, 1), V3(1, 0, 0), V3(1, 0, 1).normalized(), V3(1, 0, 3).normalized()})
    EXPECT_TRUE(inNormalCone(box, edge, n, kEps)) << n.transpose();
  for (const V3& n : {V3(-1, 0, 1).normalized(), V3(1, 0, -0.1).normalized(), V3(0, 1, 1).normalized()})
    EXPECT_FALSE(inNormalCone(box, edge, n, kEps)) << n.transpose();
}

TEST_F(BoxCones, ACornerAdmitsItsOctant) {
  const Feature corner = vertexAt(V3(0.5, 0.5, 0.5));
  ASSERT_GE(corner.id, 0);
  EXPECT_TRUE(inNormalCone(box, corner, V3(1, 1, 1).normalized(), kEps));
  EXPECT_TRUE(inNormalCone(box, corner, V3::UnitZ(), kEps));
  EXPECT_FALSE(inNormalCone(box, corner, V3(-1, 0, 1).normalized(), kEps));
  EXPECT_FALSE(inNormalCone(box, corner, -V3::UnitX(), kEps));
}

}  // namespace
}  // namespace polysim::collision
