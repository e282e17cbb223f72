#include "collision/broadphase.h"

#include <algorithm>

#include "collision/aabb.h"

namespace polysim::collision {

Eigen::AlignedBox3d worldContainer(const ObjNode& object) {
  return transformBox(object.X_WO, object.grid->container());
}

std::optional<Eigen::AlignedBox3d> overlapRegion(const ObjNode& a, const ObjNode& b, double eps) {
  const Eigen::AlignedBox3d region = grow(worldContainer(a), eps).intersection(grow(worldContainer(b), eps));
  if (region.isEmpty()) return std::nullopt;
  return region;
}

void candidatePolygonPairs(const ObjNode& a, WorldFaces& facesA, const ObjNode& b, WorldFaces& facesB,
                           const Eigen::AlignedBox3d& region, double eps, std::vector<FacePair>& pairs) {
  const VoxelGrid& gridA = *a.grid;
  const VoxelGrid& gridB = *b.grid;
  struct Node {
    VoxelCell cellA, cellB;
    Eigen::AlignedBox3d boxA, boxB;  // world
  };
  std::vector<std::uint64_t> found;
  std::vector<Node> stack;
  stack.push_back({VoxelCell{}, VoxelCell{}, transformBox(a.X_WO, gridA.cellBox({})),
                   transformBox(b.X_WO, gridB.cellBox({}))});
  // Two cells are kept while both are occupied, both meet the overlap region, and their
  // world boxes come within eps of each other. A point of A within eps of a point of B
  // lies in the region and in a cell of each that passes these tests, so nothing is lost.
  auto keep = [&](const VoxelGrid& grid, const VoxelCell& cell, const Eigen::AlignedBox3d& box) {
    return grid.occupied(cell) && box.intersects(region);
  };
  while (!stack.empty()) {
    const Node n = stack.back();
    stack.pop_back();
    if (!grow(n.boxA, eps).intersects(n.boxB)) continue;
    const bool leafA = gridA.isLeaf(n.cellA), leafB = gridB.isLeaf(n.cellB);
    if (leafA && leafB) {
      for (const int* fa = gridA.facesBegin(n.cellA); fa != gridA.facesEnd(n.cellA); ++fa) {
        const Eigen::AlignedBox3d boxFa = grow(facesA.box(*fa), eps);
        if (!boxFa.intersects(region)) continue;
        for (const int* fb = gridB.facesBegin(n.cellB); fb != gridB.facesEnd(n.cellB); ++fb)
          if (boxFa.intersects(facesB.box(*fb)))
            found.push_back(static_cast<std::uint64_t>(*fa) << 32 | static_cast<std::uint32_t>(*fb));
      }
      continue;
    }
    // Split the larger of the two cells (or the one that still can be split).
    const bool splitA = leafB || (!leafA && n.boxA.sizes().maxCoeff() >= n.boxB.sizes().maxCoeff());
    const VoxelGrid& grid = splitA ? gridA : gridB;
    const Eigen::Isometry3d& X = splitA ? a.X_WO : b.X_WO;
    VoxelCell halves[2];
    grid.children(splitA ? n.cellA : n.cellB, halves[0], halves[1]);
    for (const VoxelCell& half : halves) {
      const Eigen::AlignedBox3d box = transformBox(X, grid.cellBox(half));
      if (!keep(grid, half, box)) continue;
      if (splitA) stack.push_back({half, n.cellB, box, n.boxB});
      else stack.push_back({n.cellA, half, n.boxA, box});
    }
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  pairs.clear();
  pairs.reserve(found.size());
  for (std::uint64_t key : found) pairs.push_back({static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)});
}

}  // namespace polysim::collision
