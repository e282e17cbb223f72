#include "collision/voxel_grid.h"

#include <gtest/gtest.h>

#include <set>

#include "collision/shapes.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

using V3 = Eigen::Vector3d;

TEST(VoxelGrid, HalvesTheLongestSideEachTime) {
  const PolygonMesh slab(makeBox(V3(4, 1, 1)));
  const VoxelGrid grid(slab, 4, 0.0);
  // 4 x 1 x 1: x, x (2 x 1 x 1 cells... now 1 x 1 x 1), then x, y or z by ties -> x first.
  VoxelCell leaf{4, Eigen::Array3i(0, 0, 0)};
  const Eigen::Vector3d cell = grid.cellBox(leaf).sizes();
  EXPECT_NEAR(cell.x() * cell.y() * cell.z(), 4.0 / 16.0, 1e-12);
  EXPECT_LE(cell.maxCoeff() / cell.minCoeff(), 2.0 + 1e-12);
}

TEST(VoxelGrid, EveryFaceIsListedInTheVoxelOfItsCentroid) {
  const PolygonMesh sphere(makeIcosphere(1.0, 3));
  const int m = 12;
  const VoxelGrid grid(sphere, m, 1e-4);
  // Walk down from the root to the leaf containing each face's centroid.
  for (int f = 0; f < sphere.faceCount(); ++f) {
    const V3 c = sphere.faceBounds(f).center();
    VoxelCell cell;
    while (!grid.isLeaf(cell)) {
      ASSERT_TRUE(grid.occupied(cell));
      VoxelCell first, second;
      grid.children(cell, first, second);
      cell = grid.cellBox(first).contains(c) ? first : second;
    }
    const std::set<int> listed(grid.facesBegin(cell), grid.facesEnd(cell));
    EXPECT_TRUE(listed.count(f)) << "face " << f;
  }
}

TEST(VoxelGrid, EmptyInsideOfASphereIsNotOccupied) {
  const PolygonMesh sphere(makeIcosphere(1.0, 3));
  const VoxelGrid grid(sphere, 12, 1e-4);
  int emptyNearCentre = 0;
  for (int x = 6; x < 10; ++x)
    for (int y = 6; y < 10; ++y)
      for (int z = 6; z < 10; ++z) emptyNearCentre += !grid.occupied({12, Eigen::Array3i(x, y, z)});
  EXPECT_EQ(emptyNearCentre, 64);
}

TEST(VoxelGrid, ChoosesMoreHalvingsForFinerMeshes) {
  const int coarse = VoxelGrid::chooseHalvings(PolygonMesh(makeBox(V3(1, 1, 1))));
  const int fine = VoxelGrid::chooseHalvings(PolygonMesh(makeIcosphere(1.0, 5)));
  EXPECT_EQ(coarse, kMinVoxelHalvings);
  EXPECT_GT(fine, coarse);
  EXPECT_LE(fine, kMaxVoxelHalvings);
}

}  // namespace
}  // namespace polysim::collision
