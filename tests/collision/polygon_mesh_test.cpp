#include "collision/polygon_mesh.h"

#include <gtest/gtest.h>

#include <string>

#include "collision/shapes.h"
#include "tests/test_support.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

bool mentions(const std::vector<std::string>& problems, const std::string& text) {
  for (const std::string& p : problems)
    if (p.find(text) != std::string::npos) return true;
  return false;
}

TEST(PolygonMesh, BuiltInShapesAreValidAndClosed) {
  for (const MeshData& m : {makeBox(V3(1, 2, 3)), makeIcosphere(1.0, 2), test::makeStaple(), test::makeL(),
                            test::makeHexPrism(1.0, 0.5)}) {
    EXPECT_TRUE(validateMesh(m, true).empty()) << validateMesh(m, true).front();
    EXPECT_TRUE(PolygonMesh(m).closed());
  }
}

TEST(PolygonMesh, IcosphereHas20TimesFourToTheNTriangles) {
  EXPECT_EQ(PolygonMesh(makeIcosphere(1.0, 3)).faceCount(), 20 * 64);
}

TEST(PolygonMesh, BoxHasTwelveEdgesAndOutwardPlanes) {
  const PolygonMesh box(makeBox(V3(2, 2, 2)));
  EXPECT_EQ(box.edges().size(), 12u);
  for (int f = 0; f < box.faceCount(); ++f) EXPECT_NEAR(box.facePlane(f).offset, 1.0, 1e-12);
}

TEST(PolygonMesh, TriangulatedFloorIsOpenWithFlatInnerEdges) {
  const PolygonMesh floor(makeTriangulatedFloor(2, 2, 2));
  EXPECT_FALSE(floor.closed());
  int flat = 0;
  for (size_t e = 0; e < floor.edges().size(); ++e) flat += floor.edgeIsFlat(static_cast<int>(e));
  EXPECT_EQ(flat, 8);  // 4 inner grid edges + 4 diagonals
  EXPECT_FALSE(validateMesh(makeTriangulatedFloor(2, 2, 2), true).empty());
}

// Convex creases bound the wedge a polygon's depth is measured in (crease_depth.h): a
// box's every side; of a cup's faces, the outer walls' and the rim's outer and inner top
// edges, but not the rim's seams (flat), nor the cavity's corners (reflex); none of a
// floor's triangles (flat inside, open at the border).
TEST(PolygonMesh, ConvexCreasesAreTheSidesWhereTheSurfaceFoldsOutward) {
  const PolygonMesh box(makeBox(V3(1, 2, 3)));
  for (int f = 0; f < box.faceCount(); ++f)
    for (int i = 0; i < box.faceSize(f); ++i) EXPECT_TRUE(box.sideIsConvexCrease(f, i)) << f << " " << i;

  const PolygonMesh cup(test::makeCup(0.5, 0.6, 0.05, 0.05));
  auto sides = [&cup](int f) {
    std::string s;
    for (int i = 0; i < cup.faceSize(f); ++i) s += cup.sideIsConvexCrease(f, i) ? 'x' : '.';
    return s;
  };
  EXPECT_EQ(sides(0), "xxxx");  // bottom
  EXPECT_EQ(sides(1), "....");  // cavity floor
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(sides(2 + 3 * k), "xxxx") << "outer wall " << k;
    EXPECT_EQ(sides(3 + 3 * k), "x.x.") << "rim " << k;
    EXPECT_EQ(sides(4 + 3 * k), "x...") << "inner wall " << k;
  }

  const PolygonMesh floor(makeTriangulatedFloor(2, 2, 2));
  for (int f = 0; f < floor.faceCount(); ++f)
    for (int i = 0; i < floor.faceSize(f); ++i) EXPECT_FALSE(floor.sideIsConvexCrease(f, i)) << f << " " << i;

  // The per-face flags are the same classification.
  for (const PolygonMesh* mesh : {&box, &cup, &floor})
    for (int f = 0; f < mesh->faceCount(); ++f) {
      bool any = false;
      for (int i = 0; i < mesh->faceSize(f); ++i) {
        EXPECT_EQ(mesh->convexCreaseSides(f)[i] != 0, mesh->sideIsConvexCrease(f, i));
        any = any || mesh->sideIsConvexCrease(f, i);
      }
      EXPECT_EQ(mesh->hasConvexCrease(f), any) << "face " << f;
    }
}

TEST(PolygonMesh, RejectsEachKindOfBadFace) {
  MeshData m = makeBox(V3(1, 1, 1));
  MeshData bent = m;
  bent.vertices[7].z() += 0.02;
  EXPECT_TRUE(mentions(validateMesh(bent, false), "face 1 is not planar (vertex "));

  MeshData outOfRange = m;
  outOfRange.faces[3][1] = 8;
  EXPECT_TRUE(mentions(validateMesh(outOfRange, false), "face 3 uses vertex 8, out of range 0..7"));

  MeshData tooFew = m;
  tooFew.faces[0] = {0, 1};
  EXPECT_TRUE(mentions(validateMesh(tooFew, false), "face 0 has 2 vertices"));

  MeshData flat;
  flat.vertices = {V3(0, 0, 0), V3(1, 0, 0), V3(2, 0, 0)};
  flat.faces = {{0, 1, 2}};
  EXPECT_TRUE(mentions(validateMesh(flat, false), "face 0 has zero area"));

  MeshData open = m;
  open.faces.pop_back();
  EXPECT_TRUE(mentions(validateMesh(open, true), "is not closed"));
  EXPECT_TRUE(validateMesh(open, false).empty());

  MeshData flipped = m;
  std::reverse(flipped.faces[2].begin(), flipped.faces[2].end());
  EXPECT_TRUE(mentions(validateMesh(flipped, false), "runs the same way"));
}

// Every face of a closed mesh wound the wrong way round: consistent, closed, and
// inside-out. Its normals would point into the solid, so it is refused.
TEST(PolygonMesh, RejectsAnInsideOutClosedMesh) {
  MeshData inside = makeBox(V3(1, 2, 3));
  EXPECT_TRUE(validateMesh(inside, true).empty());
  for (auto& face : inside.faces) std::reverse(face.begin(), face.end());
  EXPECT_TRUE(mentions(validateMesh(inside, true), "is inside-out"));
  EXPECT_TRUE(mentions(validateMesh(inside, false), "is inside-out"));
  EXPECT_THROW(PolygonMesh{inside}, std::invalid_argument);
}

TEST(PolygonMesh, RejectsNonConvexFaces) {
  MeshData arrow;  // a planar but concave quadrilateral (a dart)
  arrow.vertices = {V3(0, 0, 0), V3(2, 1, 0), V3(0, 2, 0), V3(0.5, 1, 0)};
  arrow.faces = {{0, 1, 2, 3}};
  EXPECT_TRUE(mentions(validateMesh(arrow, false), "face 0 is not convex"));
  MeshData star;  // a pentagram: turns left at every corner but winds twice
  for (int k = 0; k < 5; ++k) star.vertices.emplace_back(std::cos(k * 4 * M_PI / 5), std::sin(k * 4 * M_PI / 5), 0);
  star.faces = {{0, 1, 2, 3, 4}};
  EXPECT_TRUE(mentions(validateMesh(star, false), "not convex"));
}

}  // namespace
}  // namespace polysim::collision
